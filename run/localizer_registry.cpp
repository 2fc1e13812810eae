#include "run/localizer_registry.hpp"

#include <stdexcept>

#include "run/method_options.hpp"

namespace isg::run {

void LocalizerRegistry::add(MethodInfo method) {
  if (!method.make) throw std::invalid_argument("method " + method.name + " has no factory");
  if (find(method.name) != nullptr) {
    throw std::invalid_argument("method " + method.name + " is registered twice");
  }
  for (const auto& alias : method.aliases) {
    if (find(alias) != nullptr) {
      throw std::invalid_argument("alias " + alias + " of " + method.name + " is taken");
    }
  }
  methods_.push_back(std::move(method));
}

const MethodInfo* LocalizerRegistry::find(const std::string& name) const {
  for (const auto& m : methods_) {
    if (m.name == name) return &m;
    for (const auto& alias : m.aliases) {
      if (alias == name) return &m;
    }
  }
  return nullptr;
}

std::vector<std::string> LocalizerRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& m : methods_) out.push_back(m.name);
  return out;
}

std::vector<std::string> LocalizerRegistry::acceptedNames() const {
  std::vector<std::string> out;
  for (const auto& m : methods_) {
    out.push_back(m.name);
    out.insert(out.end(), m.aliases.begin(), m.aliases.end());
  }
  return out;
}

std::string LocalizerRegistry::canonical(const std::string& name) const {
  const MethodInfo* method = find(name);
  return method != nullptr ? method->name : name;
}

std::string LocalizerRegistry::help() const {
  std::string out;
  for (const auto& m : methods_) {
    out += "  " + m.name;
    for (const auto& alias : m.aliases) out += " (or " + alias + ")";
    out += ": " + m.summary + "\n";
  }
  return out;
}

std::map<std::string, double> LocalizerRegistry::checkOptions(
    const std::string& name, const std::map<std::string, std::string>& options) const {
  const MethodInfo* method = find(name);
  if (method == nullptr) throw std::invalid_argument("unknown method " + name);
  if (method->check_options) return method->check_options(options);
  MethodOptions(options, method->name).finish();  // none known: any key is refused
  return {};
}

std::unique_ptr<slam::Localizer> LocalizerRegistry::make(const std::string& name,
                                                         const LocalizerContext& context) const {
  const MethodInfo* method = find(name);
  if (method == nullptr) throw std::invalid_argument("unknown method " + name);
  if (method->needs_plan && (context.plan == nullptr || context.agraph == nullptr)) {
    throw std::invalid_argument("method " + name + " needs a plan");
  }
  if (method->given_start && !context.start_B_T_M) {
    throw std::invalid_argument("method " + name + " needs the start pose");
  }
  checkOptions(name, context.options);
  return method->make(context);
}

}  // namespace isg::run
