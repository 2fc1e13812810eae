// The import on the five public models (ifc/tests/models, README.md there says where each comes
// from and under which licence) and on small hand-written files for the errors.

#include "ifc/ifc_import.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace isg::ifc {
namespace {

std::string modelPath(const std::string& name) {
  return std::string(ISG_SOURCE_DIR) + "/ifc/tests/models/" + name;
}

const StoreySummary* storeyNamed(const ImportResult& r, const std::string& name) {
  for (const auto& s : r.storeys) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

const bim::Wall* wallWithId(const bim::Plan& plan, const std::string& id) {
  for (const auto& level : plan.levels) {
    if (const bim::Wall* w = level.findWall(id)) return w;
  }
  return nullptr;
}

std::string importErrorOf(const std::string& text, const ImportOptions& options = {}) {
  try {
    importIfcText("t.ifc", text, options);
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "";
}

std::string stepFile(const std::string& data) {
  return "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\n"
         "FILE_NAME('t.ifc','2020-01-01T00:00:00',(''),(''),'','','');\n"
         "FILE_SCHEMA(('IFC4'));\nENDSEC;\nDATA;\n" +
         data + "ENDSEC;\nEND-ISO-10303-21;\n";
}

TEST(ImportIfc, DuplexTwoStoreysOfRevit) {
  const ImportResult r = importIfc(modelPath("duplex.ifc"), {});
  EXPECT_EQ(r.schema, "IFC2X3");
  EXPECT_EQ(r.metres_per_unit, 1.0);
  ASSERT_EQ(r.plan.levels.size(), 2u);
  EXPECT_EQ(r.plan.levels[0].id, "Level 1");
  EXPECT_EQ(r.plan.levels[1].id, "Level 2");
  // The foundation and the roof are storeys, not levels, and the summary says why.
  ASSERT_NE(storeyNamed(r, "T/FDN"), nullptr);
  EXPECT_EQ(storeyNamed(r, "T/FDN")->level_id, "");
  EXPECT_EQ(storeyNamed(r, "Roof")->why_not, "no wall rises 1.500 m above its floor");
  const StoreySummary& l1 = *storeyNamed(r, "Level 1");
  EXPECT_EQ(l1.rooms, 10);
  EXPECT_EQ(l1.doors, 6);
  // Level 1's floor is its rooms' floor (19 mm above the storey's elevation).
  EXPECT_NEAR(r.plan.levels[0].elevation, 0.019, 1e-3);
  // The north exterior wall: Revit centres its axis, 417 mm thick, 8.8 m long, up to 3.1 m.
  const bim::Wall* wall = wallWithId(r.plan, "2O2Fr$t4X7Zf8NOew3FNtn");
  ASSERT_NE(wall, nullptr);
  EXPECT_NEAR(wall->thickness, 0.417, 1e-3);
  EXPECT_NEAR((wall->end - wall->start).norm(), 8.8, 1e-3);
  EXPECT_NEAR(wall->start.y(), -0.2085, 1e-3);
  EXPECT_NEAR(wall->height + r.plan.levels[0].elevation, 3.1, 1e-3);
  EXPECT_NEAR(wall->base, 0.0, 1e-9);
  // Doors take their opening's clear width (the door's mesh includes its frame).
  const bim::Door* door = r.plan.levels[1].findDoor("1hOSvn6df7F8_7GcBWlSFK");
  ASSERT_NE(door, nullptr);
  EXPECT_NEAR(door->width, 0.864, 1e-3);
  // Each element left out or simplified is in the log, by GlobalId.
  EXPECT_THAT(r.log, testing::Contains(
                         testing::HasSubstr("dropped window 1Eo2$BaHX42AEkDvQQDocD \"M_Skylight")));
  EXPECT_THAT(r.log, testing::Contains(testing::HasSubstr("dropped wall 2O2Fr$t4X7Zf8NOew3FKRH")));
  // Each dwelling's straight flight joins the two levels: 3.1 m up over 3.75 m, 0.914 m wide,
  // its top end trimmed 23 mm clear of the party wall it is built into.
  ASSERT_EQ(r.plan.levels[0].stairs.size(), 2u);
  const bim::Stair* stair = r.plan.levels[0].findStair("1oKjKg9PD3fP1iIwXLh3lK");
  ASSERT_NE(stair, nullptr);
  EXPECT_EQ(stair->to, "Level 2");
  EXPECT_NEAR(stair->width, 0.914, 1e-3);
  EXPECT_NEAR((stair->end - stair->start).norm(), 3.750, 1e-3);
  EXPECT_GT(stair->end.y(), stair->start.y());  // it climbs north
  EXPECT_THAT(r.log, testing::Contains(testing::HasSubstr(
                         "its top end trimmed by 0.023 m to clear wall 2O2Fr$t4X7Zf8NOew3FNbT")));
}

TEST(ImportIfc, FlightsToLandingsAreDroppedAndSaidSo) {
  // Office_A's stairs are dog-legs (two flights to a half landing at 2.084 m); the Renga house's
  // is an L (19 risers to 2.85 m, 4 more to 3.45 m) and its entrance steps rise from the ground.
  for (const char* file : {"Office_A_20110811.ifc", "xbim-House.ifc"}) {
    SCOPED_TRACE(file);
    const ImportResult r = importIfc(modelPath(file), {});
    for (const auto& level : r.plan.levels) EXPECT_TRUE(level.stairs.empty());
    EXPECT_THAT(r.log, testing::Contains(testing::HasSubstr("a flight to or from a half landing")));
  }
}

TEST(ImportIfc, StoreysChosenByName) {
  ImportOptions options;
  options.storeys = {"Level 2"};
  const ImportResult r = importIfc(modelPath("duplex.ifc"), options);
  ASSERT_EQ(r.plan.levels.size(), 1u);
  EXPECT_EQ(r.plan.levels[0].id, "Level 2");
  options.storeys = {"Level 3"};
  EXPECT_EQ(importErrorOf(common::readCheckedFile(modelPath("duplex.ifc"), kMaxIfcBytes), options),
            "t.ifc: no storey named \"Level 3\" (--storey); its storeys: \"T/FDN\", \"Level 1\", "
            "\"Level 2\", \"Roof\"");
  options.storeys = {"Roof"};
  EXPECT_EQ(importErrorOf(common::readCheckedFile(modelPath("duplex.ifc"), kMaxIfcBytes), options),
            "t.ifc: storey \"Roof\" has no wall rising 1.500 m above its floor: nothing to import");
}

TEST(ImportIfc, RengaInMillimetres) {
  const ImportResult r = importIfc(modelPath("xbim-House.ifc"), {});
  EXPECT_EQ(r.metres_per_unit, 0.001);
  ASSERT_EQ(r.plan.levels.size(), 2u);
  // Renga's 400 mm walls come out 0.4 m thick.
  const bim::Wall* wall = wallWithId(r.plan, "2ScB0b_Z1FQRFCzNdZeouf");
  ASSERT_NE(wall, nullptr);
  EXPECT_NEAR(wall->thickness, 0.4, 1e-6);
  // Gable walls are taken at their eaves, and the log says so.
  EXPECT_THAT(r.log, testing::Contains(testing::HasSubstr("(a gable or a sloped top)")));
}

TEST(ImportIfc, ColumnsAreReadAsColumns) {
  // The Renga house's five IfcColumn ("Колонна - прямоугольная: 200x200 мм"): square 0.2 m
  // columns, each on the level it stands on, standing from its floor.
  const ImportResult r = importIfc(modelPath("xbim-House.ifc"), {});
  int columns = 0;
  for (const auto& level : r.plan.levels) {
    for (const auto& column : level.columns) {
      ++columns;
      EXPECT_FALSE(column.round()) << column.id;
      EXPECT_NEAR(column.size.x(), 0.2, 1e-6) << column.id;
      EXPECT_NEAR(column.size.y(), 0.2, 1e-6) << column.id;
      EXPECT_GT(column.height - column.base, 1.5) << column.id;
      EXPECT_NE(column.name.find("200x200"), std::string::npos) << column.name;
    }
  }
  EXPECT_EQ(columns, 5);
  // Every other model has none.
  for (const char* file : {"duplex.ifc", "IfcOpenHouse_IFC4.ifc", "xbim-SampleHouse4.ifc"}) {
    for (const auto& level : importIfc(modelPath(file), {}).plan.levels) {
      EXPECT_TRUE(level.columns.empty()) << file;
    }
  }
}

TEST(ImportIfc, EveryModelGivesAPlanTheParserAccepts) {
  struct Expected {
    const char* file;
    std::size_t levels, walls, doors, rooms;
  };
  // What the import makes of each model today (docs/formats.md, "Importing IFC", explains the
  // differences from the models' own counts).
  for (const Expected& e :
       {Expected{"duplex.ifc", 2, 35, 14, 20}, Expected{"Office_A_20110811.ifc", 2, 458, 106, 99},
        // IfcOpenHouse has no IfcSpace: its one room is the free space its four walls enclose.
        Expected{"IfcOpenHouse_IFC4.ifc", 1, 4, 1, 1},
        Expected{"xbim-SampleHouse4.ifc", 1, 6, 3, 3}, Expected{"xbim-House.ifc", 2, 39, 19, 13}}) {
    SCOPED_TRACE(e.file);
    const ImportResult r = importIfc(modelPath(e.file), {});
    std::size_t walls = 0, doors = 0, rooms = 0;
    for (const auto& level : r.plan.levels) {
      walls += level.walls.size(), doors += level.doors.size(), rooms += level.rooms.size();
    }
    EXPECT_EQ(r.plan.levels.size(), e.levels);
    EXPECT_EQ(walls, e.walls);
    EXPECT_EQ(doors, e.doors);
    EXPECT_EQ(rooms, e.rooms);
    EXPECT_EQ(r.plan_json["imported_from"]["file"], e.file);
  }
}

// Every element keeps the GlobalId of what it was made from, as the model's own text has it.
TEST(ImportIfc, EveryElementKeepsItsGlobalId) {
  const std::string text = common::readCheckedFile(modelPath("duplex.ifc"), kMaxIfcBytes);
  const auto inModel = [&](const std::string& guid) {
    return bim::isIfcGlobalId(guid) && text.find("('" + guid + "'") != std::string::npos;
  };
  const ImportResult r = importIfc(modelPath("duplex.ifc"), {});
  std::size_t rooms_kept = 0;
  for (const auto& level : r.plan.levels) {
    EXPECT_TRUE(inModel(level.ifc_guid)) << level.id;
    for (const auto& wall : level.walls) EXPECT_TRUE(inModel(wall.ifc_guid)) << wall.id;
    for (const auto& door : level.doors) EXPECT_TRUE(inModel(door.ifc_guid)) << door.id;
    for (const auto& window : level.windows) EXPECT_TRUE(inModel(window.ifc_guid)) << window.id;
    for (const auto& room : level.rooms) rooms_kept += inModel(room.ifc_guid);
  }
  // Its 20 rooms are its IfcSpaces.
  EXPECT_EQ(rooms_kept, 20u);
  // A room the import finds itself (IfcOpenHouse has no IfcSpace) has none.
  const ImportResult house = importIfc(modelPath("IfcOpenHouse_IFC4.ifc"), {});
  EXPECT_EQ(house.plan.levels[0].rooms[0].ifc_guid, "");
  EXPECT_EQ(house.plan.levels[0].walls[0].ifc_guid, "3g46_woBL6sugXeY5_WP6n");
}

TEST(ImportIfc, BadModels) {
  EXPECT_EQ(importErrorOf(stepFile("#1=IFCBUILDINGSTOREY('1YvctVUKr0kugbFTf53O9L',$,'G',$,$,$,$,$,"
                                   ".ELEMENT.,0.);\n")),
            "t.ifc: no IfcProject: not a readable IFC model");
  EXPECT_EQ(importErrorOf(stepFile("#1=IFCPROJECT('0YvctVUKr0kugbFTf53O9L',$,'P',$,$,$,$,$,$);\n")),
            "t.ifc: no IfcBuildingStorey: the model has no storey to import");
  EXPECT_EQ(importErrorOf(stepFile("#1=IFCPROJECT('0YvctVUKr0kugbFTf53O9L',$,'P',$,$,$,$,$,$);\n"
                                   "#2=IFCBUILDINGSTOREY('1YvctVUKr0kugbFTf53O9L',$,'G',$,$,$,$,$,"
                                   ".ELEMENT.,0.);\n")),
            "t.ifc: no wall the import could read: nothing to import");
  const std::string house =
      common::readCheckedFile(modelPath("IfcOpenHouse_IFC4.ifc"), kMaxIfcBytes);
  EXPECT_EQ(importErrorOf(house.substr(0, house.size() / 2)),
            "t.ifc: truncated: the file does not end with \"END-ISO-10303-21;\"");
}

TEST(ImportIfc, AModelThatCrashesIfcppIsABadModel) {
  // IFC++ dereferences a polyline's missing first point (found by ci/fuzz): it runs in a child
  // process, and the crash is reported as what is wrong with the file.
  const std::string text =
      common::readCheckedFile(modelPath("bad/ifcpp_null_polyline_point.ifc"), kMaxIfcBytes);
  EXPECT_THAT(importErrorOf(text), testing::StartsWith("t.ifc: IFC++ stopped with signal "));
}

TEST(ImportIfc, AModelInSurveyCoordinatesIsNamed) {
  // small.ifc with its site placed 20 km east: beyond the plan's ±10 km.
  std::string text = common::readCheckedFile(modelPath("small.ifc"), kMaxIfcBytes);
  const std::string site = "#31=IFCLOCALPLACEMENT($,#21);";
  ASSERT_NE(text.find(site), std::string::npos);
  text.replace(text.find(site), site.size(),
               "#31=IFCLOCALPLACEMENT($,#24);\n#24=IFCAXIS2PLACEMENT3D(#23,$,$);\n"
               "#23=IFCCARTESIANPOINT((20000.,500.,0.));");
  EXPECT_EQ(importErrorOf(text),
            "t.ifc: wall 7YvctVUKr0kugbFTf53O9L \"Wall A\" lies 20.005 km from the model's origin, "
            "beyond the plan's ±10.000 km: the model is placed in site or survey coordinates (its "
            "IfcSite's placement); move its site's placement near the origin in the authoring "
            "tool");
}

TEST(ImportIfc, AMissingFileIsNamed) {
  try {
    importIfc("/nonexistent/model.ifc", {});
    FAIL();
  } catch (const common::InputError& e) {
    EXPECT_THAT(e.what(), testing::StartsWith("/nonexistent/model.ifc: "));
  }
}

}  // namespace
}  // namespace isg::ifc
