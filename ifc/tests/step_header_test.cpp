// The file checks before IFC++ reads anything: each bad file gets its exact message.
#include "ifc/step_header.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/input_error.hpp"

namespace isg::ifc {
namespace {

const std::string kHeader =
    "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('ViewDefinition [CoordinationView]'),'2;1');\n"
    "FILE_NAME('a.ifc','2020-01-01T00:00:00',('Ann'),('Org'),'Pre 1.0','Tool''s 2',$);\n";

std::string fileWithSchema(const std::string& schema) {
  return kHeader + "FILE_SCHEMA(('" + schema + "'));\nENDSEC;\nDATA;\nENDSEC;\nEND-ISO-10303-21;\n";
}

std::string headerErrorOf(const std::string& text) {
  try {
    readStepHeader("m.ifc", text);
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(StepHeader, ReadsTheSchemaAndTheTool) {
  const StepHeader h = readStepHeader("m.ifc", fileWithSchema("IFC2X3"));
  EXPECT_EQ(h.schema, "IFC2X3");
  EXPECT_EQ(h.application, "Pre 1.0 / Tool's 2");
  EXPECT_EQ(readStepHeader("m.ifc", fileWithSchema("Ifc4")).schema, "IFC4");
}

TEST(StepHeader, NotIfc) {
  EXPECT_EQ(headerErrorOf("{\"format\": \"isg.plan\"}"),
            "m.ifc: not an IFC file: an IFC (STEP, ISO 10303-21) file starts with "
            "\"ISO-10303-21;\"");
  EXPECT_EQ(headerErrorOf(""), headerErrorOf("PK\x03\x04 a zip"));
}

TEST(StepHeader, OtherSchemas) {
  EXPECT_EQ(headerErrorOf(fileWithSchema("IFC4X3_ADD2")),
            "m.ifc: schema IFC4X3_ADD2 is not supported: the import reads IFC2X3 and IFC4 "
            "(export the model as one of them)");
  EXPECT_THAT(headerErrorOf(fileWithSchema("IFC2X2_FINAL")), testing::HasSubstr("IFC2X2_FINAL"));
  EXPECT_THAT(headerErrorOf(fileWithSchema("IFC4X1")), testing::HasSubstr("not supported"));
}

TEST(StepHeader, NoSchema) {
  EXPECT_EQ(headerErrorOf(kHeader + "ENDSEC;\nDATA;\nENDSEC;\nEND-ISO-10303-21;\n"),
            "m.ifc: no FILE_SCHEMA in the file's header: which IFC schema it follows is unknown");
}

TEST(StepHeader, Truncated) {
  const std::string whole = fileWithSchema("IFC4");
  EXPECT_EQ(headerErrorOf(whole.substr(0, whole.size() - 12)),
            "m.ifc: truncated: the file does not end with \"END-ISO-10303-21;\"");
}

TEST(StepHeader, AByteOrderMarkAndBlankLinesAreFine) {
  EXPECT_EQ(readStepHeader("m.ifc", "\xEF\xBB\xBF\n " + fileWithSchema("IFC4") + "\n\n").schema,
            "IFC4");
}

TEST(CountInstances, CountsEntitiesOfTheTypesNotTextInStrings) {
  const std::string text =
      "DATA;\n#1=IFCWALL('a',$,'x=IFCWALL(',$);\n#2 = ifcwall ('b');\n"
      "#3=IFCWALLSTANDARDCASE('c');\n#4=IFCWALLTYPE('d');\n#5=IFCSPACE('it''s =IFCWALL(');\n"
      "#6=IFCBUILDINGSTOREY('e');\nENDSEC;\n";
  EXPECT_EQ(countInstances(text, {"IFCWALL"}), 2u);
  EXPECT_EQ(countInstances(text, {"IFCWALL", "IFCWALLSTANDARDCASE"}), 3u);
  EXPECT_EQ(countInstances(text, {"IFCBUILDINGSTOREY"}), 1u);
  EXPECT_EQ(countInstances(text, {"IFCDOOR"}), 0u);
}

TEST(CheckStepStrings, AStringLeftOpenIsNamedByItsLine) {
  const std::string good =
      "ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#1=IFCWALL('it''s',$,'a',$);\n"
      "#2=IFCSPACE('b');\nENDSEC;\nEND-ISO-10303-21;\n";
  EXPECT_NO_THROW(checkStepStrings("m.ifc", good));
  std::string open = good;
  open.replace(open.find("'a',"), 4, "'a,");  // the last string of its line left open
  try {
    checkStepStrings("m.ifc", open);
    FAIL() << "accepted";
  } catch (const common::InputError& e) {
    EXPECT_EQ(e.reason(),
              "line 5: the string 'a,$);… is never closed: it runs into the entity "
              "instance on line 6 (a quote is missing)");
  }
  std::string at_end = good;
  at_end.replace(at_end.find("'b'"), 3, "'b");
  try {
    checkStepStrings("m.ifc", at_end);
    FAIL() << "accepted";
  } catch (const common::InputError& e) {
    EXPECT_EQ(e.reason(),
              "line 6: the string 'b);… is never closed: the file ends inside it (a quote is "
              "missing)");
  }
}

}  // namespace
}  // namespace isg::ifc
