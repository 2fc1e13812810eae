#pragma once

#include <map>
#include <set>
#include <string>

namespace isg::run {

// A method's settings from the command line (--method-option KEY=VALUE): each method reads the
// keys it knows and then calls finish(), so a misspelt key is an error, not a silent default.
// Every key read is kept with the value the method uses, given or its default (effective()):
// what a run folder records as the options it ran with.
class MethodOptions {
 public:
  MethodOptions(const std::map<std::string, std::string>& options, std::string method)
      : options_(options), method_(std::move(method)) {}

  // The key's value as a number in [lo, hi], or `fallback` when not given. Throws
  // std::invalid_argument naming the method, the key and the value.
  double number(const std::string& key, double fallback, double lo, double hi);
  int integer(const std::string& key, int fallback, int lo, int hi);
  // Throws std::invalid_argument for a key no read asked for, listing the known ones.
  void finish() const;
  // Each key read so far with the value used: the given one, else the default.
  const std::map<std::string, double>& effective() const { return effective_; }

 private:
  const std::map<std::string, std::string>& options_;
  std::string method_;
  std::set<std::string> known_;
  std::map<std::string, double> effective_;
};

}  // namespace isg::run
