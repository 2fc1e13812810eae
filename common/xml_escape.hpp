#pragma once

#include <string>

namespace isg::common {

// Text for XML (MJCF worlds, SVG pictures), in element content or a double-quoted attribute (every
// attribute we write is): & < > " as entities, an apostrophe as it is; the control characters
// XML 1.0 cannot hold at all, not even as references (all below 0x20 but the tab, and DEL), as '?'.
// Plans reject them; a file name given on the command line may still hold one.
std::string xmlEscape(const std::string& text);

}  // namespace isg::common
