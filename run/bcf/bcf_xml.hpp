#pragma once

#include <ctime>
#include <string>
#include <vector>

#include "run/bcf/bcf_topics.hpp"

namespace isg::run::bcf {

// The XML documents of a BCF 3.0 archive, as buildingSMART's schemas (BCF-XML, release 3.0) lay
// them out; run/bcf/tests validates each against those schemas.

// bcf.version: the version document buildingSMART publishes, but for the line break inside the
// element: the schema gives Version an empty content, and a strict validator (xmllint) refuses the
// published file's whitespace as character content.
std::string versionXml();
// extensions.xml: the topic type, statuses and labels the topics use.
std::string extensionsXml();
// <topic>/markup.bcf: the topic, created at `created` (UTC) by `author`; its one viewpoint names
// viewpoint.bcfv and, when `with_snapshot`, snapshot.png.
std::string markupXml(const Topic& topic, std::time_t created, const std::string& author,
                      bool with_snapshot);
// <topic>/viewpoint.bcfv: the element selected (by its IFC GlobalId, else by its plan id as
// isg's own), every other element visible, the perspective camera, and the element's outline as
// lines.
std::string viewpointXml(const Topic& topic);

// `when` as xs:dateTime in UTC: "2026-12-07T08:30:00Z".
std::string isoDateTime(std::time_t when);

}  // namespace isg::run::bcf
