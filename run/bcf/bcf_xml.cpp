#include "run/bcf/bcf_xml.hpp"

#include <cstdio>

#include "common/xml_escape.hpp"
#include "run/bcf/bcf_topics.hpp"

namespace isg::run::bcf {

namespace {

constexpr const char* kXmlDeclaration = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";

std::string element(const std::string& name, const std::string& text) {
  return "<" + name + ">" + common::xmlEscape(text) + "</" + name + ">";
}

std::string number(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.4f", value);
  return text;
}

std::string xyz(const std::string& name, const Eigen::Vector3d& v) {
  return "<" + name + "><X>" + number(v.x()) + "</X><Y>" + number(v.y()) + "</Y><Z>" +
         number(v.z()) + "</Z></" + name + ">";
}

std::string list(const std::string& outer, const std::string& inner,
                 const std::vector<std::string>& values) {
  std::string xml = "  <" + outer + ">\n";
  for (const std::string& value : values) xml += "    " + element(inner, value) + "\n";
  return xml + "  </" + outer + ">\n";
}

}  // namespace

std::string isoDateTime(std::time_t when) {
  std::tm utc{};
  gmtime_r(&when, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

std::string versionXml() {
  return std::string(kXmlDeclaration) +
         "<Version VersionId=\"3.0\" xsi:noNamespaceSchemaLocation=\"https://raw.githubusercontent."
         "com/buildingSMART/BCF-XML/release_3_0/Schemas/version.xsd\"\n"
         "    xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\"></Version>\n";
}

std::string extensionsXml() {
  return std::string(kXmlDeclaration) + "<Extensions>\n" +
         list("TopicTypes", "TopicType", {kTopicType}) +
         list("TopicStatuses", "TopicStatus", {kTopicStatus}) +
         list("TopicLabels", "TopicLabel", topicLabels()) + "</Extensions>\n";
}

std::string markupXml(const Topic& topic, std::time_t created, const std::string& author,
                      bool with_snapshot) {
  std::string xml = std::string(kXmlDeclaration) + "<Markup>\n";
  xml += "  <Topic Guid=\"" + topic.guid + "\" TopicType=\"" + kTopicType + "\" TopicStatus=\"" +
         kTopicStatus + "\">\n";
  xml += "    " + element("Title", topic.title) + "\n";
  xml += "    <Labels>";
  for (const std::string& label : topic.labels) xml += element("Label", label);
  xml += "</Labels>\n";
  xml += "    " + element("CreationDate", isoDateTime(created)) + "\n";
  xml += "    " + element("CreationAuthor", author) + "\n";
  xml += "    " + element("Description", topic.description) + "\n";
  xml += "    <Viewpoints>\n      <ViewPoint Guid=\"" + topic.viewpoint_guid + "\">" +
         element("Viewpoint", "viewpoint.bcfv") +
         (with_snapshot ? element("Snapshot", "snapshot.png") : "") +
         "<Index>0</Index></ViewPoint>\n    </Viewpoints>\n";
  return xml + "  </Topic>\n</Markup>\n";
}

std::string viewpointXml(const Topic& topic) {
  std::string xml = std::string(kXmlDeclaration) + "<VisualizationInfo Guid=\"" +
                    topic.viewpoint_guid + "\">\n  <Components>\n";
  if (!topic.element_id.empty()) {
    xml += "    <Selection>\n      <Component";
    if (!topic.ifc_guid.empty()) xml += " IfcGuid=\"" + common::xmlEscape(topic.ifc_guid) + "\"";
    xml += ">" + element("OriginatingSystem", "isg") +
           element("AuthoringToolId", topic.element_id) + "</Component>\n    </Selection>\n";
  }
  xml += "    <Visibility DefaultVisibility=\"true\"/>\n  </Components>\n";
  const TopicCamera& camera = topic.camera;
  xml += "  <PerspectiveCamera>\n    " + xyz("CameraViewPoint", camera.eye) + "\n    " +
         xyz("CameraDirection", camera.direction()) + "\n    " +
         xyz("CameraUpVector", camera.up()) + "\n    " +
         element("FieldOfView", number(camera.vertical_fov_deg)) + "\n    " +
         element("AspectRatio", number(camera.aspect)) + "\n  </PerspectiveCamera>\n";
  xml += "  <Lines>\n";
  for (const auto& [from, to] : topic.outline.edges()) {
    xml += "    <Line>" + xyz("StartPoint", from) + xyz("EndPoint", to) + "</Line>\n";
  }
  xml += "  </Lines>\n";
  return xml + "</VisualizationInfo>\n";
}

}  // namespace isg::run::bcf
