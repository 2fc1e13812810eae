// Never run: an executable linked with PCL alone, whose link line tells what PCL itself brings
// (localizers_link_no_codec.sh subtracts it from the localizers'). Kept out of tests/*.cpp, which
// make slam_tests: its main would replace the test runner's, and no test would run.
int main() { return 0; }
