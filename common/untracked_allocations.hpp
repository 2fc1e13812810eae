#pragma once

// Under AddressSanitizer (ci/sanitize), LeakSanitizer reports every allocation not freed by exit.
// Two libraries we call keep memory for ever by design or by a bug we cannot fix: Mesa's EGL and
// GL drivers (240 bytes of set-up; built without frame pointers, so no suppression file can name
// them: sim/renderer.cpp) and IFC++'s geometry conversion (it never deletes the collector carve's
// CSG makes for each boolean operation, SolidModelConverter.h: ifc/ifc_model.cpp). While an
// UntrackedAllocations lives, this thread's allocations are not tracked; outside the few calls
// into those libraries that hold one, everything is. Without the sanitizer it does nothing.

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ISG_WITH_LSAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define ISG_WITH_LSAN 1
#endif
#ifdef ISG_WITH_LSAN
#include <sanitizer/lsan_interface.h>
#endif

namespace isg::common {

struct UntrackedAllocations {
  UntrackedAllocations() {
#ifdef ISG_WITH_LSAN
    __lsan_disable();
#endif
  }
  ~UntrackedAllocations() {
#ifdef ISG_WITH_LSAN
    __lsan_enable();
#endif
  }
  UntrackedAllocations(const UntrackedAllocations&) = delete;
  UntrackedAllocations& operator=(const UntrackedAllocations&) = delete;
};

}  // namespace isg::common
