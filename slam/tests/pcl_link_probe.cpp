// Never run: an executable linked with PCL alone, whose link line tells what PCL itself brings
// (localizers_link_no_codec.sh subtracts it from the localizers').
int main() { return 0; }
