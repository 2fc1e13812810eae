#include "run/localizer_registry.hpp"

#include <stdexcept>

namespace isg::run {

void LocalizerRegistry::add(MethodInfo method) {
  if (!method.make) throw std::invalid_argument("method " + method.name + " has no factory");
  if (find(method.name) != nullptr) {
    throw std::invalid_argument("method " + method.name + " is registered twice");
  }
  methods_.push_back(std::move(method));
}

const MethodInfo* LocalizerRegistry::find(const std::string& name) const {
  for (const auto& m : methods_) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

std::vector<std::string> LocalizerRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& m : methods_) out.push_back(m.name);
  return out;
}

std::string LocalizerRegistry::help() const {
  std::string out;
  for (const auto& m : methods_) out += "  " + m.name + ": " + m.summary + "\n";
  return out;
}

std::unique_ptr<slam::Localizer> LocalizerRegistry::make(const std::string& name,
                                                         const LocalizerContext& context) const {
  const MethodInfo* method = find(name);
  if (method == nullptr) throw std::invalid_argument("unknown method " + name);
  if (method->needs_plan && context.agraph == nullptr) {
    throw std::invalid_argument("method " + name + " needs a plan");
  }
  if (method->given_start && !context.start_B_T_M) {
    throw std::invalid_argument("method " + name + " needs the start pose");
  }
  return method->make(context);
}

}  // namespace isg::run
