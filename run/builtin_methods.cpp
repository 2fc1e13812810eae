#include "run/builtin_methods.hpp"

namespace isg::run {

LocalizerRegistry builtinMethods() {
  LocalizerRegistry registry;
  addISGraphs(registry);
  addAmcl(registry);
  addNdtUkf(registry);
  addSGraph(registry);
  addDeadReckoning(registry);
  return registry;
}

}  // namespace isg::run
