#include "ifc/ifc_importer.hpp"

#include <ifcpp/IFC4/include/IfcBuildingStorey.h>
#include <ifcpp/IFC4/include/IfcColumn.h>
#include <ifcpp/IFC4/include/IfcCurtainWall.h>
#include <ifcpp/IFC4/include/IfcDoor.h>
#include <ifcpp/IFC4/include/IfcLengthMeasure.h>
#include <ifcpp/IFC4/include/IfcMaterialLayer.h>
#include <ifcpp/IFC4/include/IfcMaterialLayerSet.h>
#include <ifcpp/IFC4/include/IfcMaterialLayerSetUsage.h>
#include <ifcpp/IFC4/include/IfcNonNegativeLengthMeasure.h>
#include <ifcpp/IFC4/include/IfcOpeningElement.h>
#include <ifcpp/IFC4/include/IfcOpeningElementTypeEnum.h>
#include <ifcpp/IFC4/include/IfcRelAggregates.h>
#include <ifcpp/IFC4/include/IfcRelAssociatesMaterial.h>
#include <ifcpp/IFC4/include/IfcRelContainedInSpatialStructure.h>
#include <ifcpp/IFC4/include/IfcRelFillsElement.h>
#include <ifcpp/IFC4/include/IfcRelVoidsElement.h>
#include <ifcpp/IFC4/include/IfcSpace.h>
#include <ifcpp/IFC4/include/IfcStair.h>
#include <ifcpp/IFC4/include/IfcStairFlight.h>
#include <ifcpp/IFC4/include/IfcWall.h>
#include <ifcpp/IFC4/include/IfcWindow.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <map>
#include <set>

#include "bim/free_space_rooms.hpp"
#include "bim/limits.hpp"
#include "bim/plan.hpp"
#include "bim/plan_json.hpp"
#include "bim/plan_parser.hpp"
#include "bim/polygon.hpp"
#include "bim/stairs.hpp"
#include "common/json_reader.hpp"
#include "common/limits.hpp"
#include "common/plural.hpp"
#include "ifc/ifcpp_model.hpp"

namespace isg::ifc::importer {

std::string fmt(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3f", std::abs(v) < 5e-4 ? 0.0 : v);
  return buffer;
}

// Valid UTF-8 (JSON needs it; a header's bytes may be in any encoding): each byte that does not
// start or continue a well-formed sequence becomes U+FFFD.
std::string validUtf8(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    std::size_t length = c < 0x80           ? 1
                         : (c >> 5) == 0x6  ? 2
                         : (c >> 4) == 0xE  ? 3
                         : (c >> 3) == 0x1E ? 4
                                            : 0;
    bool ok = length > 0 && i + length <= text.size();
    std::uint32_t code = length == 1   ? c
                         : length == 2 ? (c & 0x1F)
                         : length == 3 ? (c & 0x0F)
                                       : (c & 0x07);
    for (std::size_t k = 1; ok && k < length; ++k) {
      const auto next = static_cast<unsigned char>(text[i + k]);
      ok = (next >> 6) == 0x2;
      code = (code << 6) | (next & 0x3F);
    }
    // Overlong forms, surrogates and code points beyond U+10FFFF are not UTF-8 either.
    static constexpr std::uint32_t kLeast[] = {0, 0, 0x80, 0x800, 0x10000};
    ok = ok && code >= kLeast[length] && code <= 0x10FFFF && !(code >= 0xD800 && code <= 0xDFFF);
    if (ok) {
      out.append(text, i, length);
      i += length;
    } else {
      out += "\xEF\xBF\xBD";
      ++i;
    }
  }
  return out;
}

std::string cleanText(std::string text, std::size_t max_bytes) {
  text = validUtf8(text);
  for (char& c : text) {
    if ((static_cast<unsigned char>(c) < 0x20) || c == 0x7F) c = ' ';
  }
  if (text.size() > max_bytes) {
    text.resize(max_bytes);
    // Not in the middle of a UTF-8 sequence.
    while (!text.empty() && (static_cast<unsigned char>(text.back()) & 0xC0) == 0x80) {
      text.pop_back();
    }
    if (!text.empty() && (static_cast<unsigned char>(text.back()) & 0x80)) text.pop_back();
  }
  return text;
}

std::string describe(const std::string& kind, const shared_ptr<IfcRoot>& object) {
  const std::string name = object ? labelText(object->m_Name) : "";
  return kind + " " + globalIdOf(object) + (name.empty() ? "" : " \"" + name + "\"");
}

void collectSpaces(const shared_ptr<IfcObjectDefinition>& parent,
                   std::vector<shared_ptr<IfcSpace>>& spaces, int depth) {
  if (depth > 8) return;
  forEachRelation(parent->m_IsDecomposedBy_inverse, [&](const shared_ptr<IfcRelAggregates>& rel) {
    for (const auto& child : rel->m_RelatedObjects) {
      if (auto space = dynamic_pointer_cast<IfcSpace>(child)) {
        spaces.push_back(space);
        collectSpaces(space, spaces, depth + 1);
      }
    }
  });
}

// The total thickness of the wall's material layer set, when it has one.
std::optional<double> layerSetThickness(const shared_ptr<IfcElement>& element, double unit) {
  std::optional<double> total;
  forEachRelation(element->m_HasAssociations_inverse, [&](const shared_ptr<IfcRelAssociates>& r) {
    auto material = dynamic_pointer_cast<IfcRelAssociatesMaterial>(r);
    if (!material) return;
    auto usage = dynamic_pointer_cast<IfcMaterialLayerSetUsage>(material->m_RelatingMaterial);
    if (!usage || !usage->m_ForLayerSet) return;
    double sum = 0.0;
    for (const auto& layer : usage->m_ForLayerSet->m_MaterialLayers) {
      if (layer && layer->m_LayerThickness) sum += layer->m_LayerThickness->m_value * unit;
    }
    total = sum;
  });
  return total;
}

// The body of an element, or of its parts (a curtain wall is often only its plates and members).
Mesh bodyWithParts(BodyReader& reader, const shared_ptr<IfcProduct>& product,
                   Eigen::Matrix4d* placement) {
  Body body = reader.read(product);
  if (placement) *placement = body.placement;
  if (!body.faces.empty()) return body.faces;
  Mesh parts;
  forEachRelation(product->m_IsDecomposedBy_inverse, [&](const shared_ptr<IfcRelAggregates>& rel) {
    for (const auto& child : rel->m_RelatedObjects) {
      if (auto part = dynamic_pointer_cast<IfcProduct>(child)) {
        Body part_body = reader.read(part);
        parts.insert(parts.end(), part_body.faces.begin(), part_body.faces.end());
      }
    }
  });
  return parts;
}

std::string Importer::uniqueId(const std::string& wanted, const std::string& suffix) {
  std::string id = cleanText(wanted.empty() ? "unnamed" : wanted, common::limits::kMaxIdBytes - 24);
  if (id == bim::kOutside) id += "-";
  std::string candidate = id;
  if (used_ids_.count(candidate) && !suffix.empty()) candidate = id + "@" + cleanText(suffix, 20);
  for (int n = 2; used_ids_.count(candidate); ++n) candidate = id + "#" + std::to_string(n);
  used_ids_.insert(candidate);
  return candidate;
}

void Importer::readStoreys() {
  for (const auto& [id, entity] : loaded_.model->getMapIfcEntities()) {
    auto storey = dynamic_pointer_cast<IfcBuildingStorey>(entity);
    if (!storey) continue;
    StoreyRecord record;
    record.storey = storey;
    record.global_id = globalIdOf(storey);
    record.name = labelText(storey->m_Name);
    if (storey->m_ObjectPlacement) {
      record.elevation = bodies_.placementOf(storey)(2, 3);
    } else if (storey->m_Elevation) {
      record.elevation = storey->m_Elevation->m_value * unit_;
    }
    std::vector<shared_ptr<IfcSpace>> spaces;
    collectSpaces(storey, spaces);
    // IFC aggregates a storey's spaces (IfcRelAggregates); some exporters (FreeCAD's through
    // IfcOpenShell) list them among its contained elements instead. Taken as its spaces all the
    // same, and said.
    forEachRelation(storey->m_ContainsElements_inverse,
                    [&](const shared_ptr<IfcRelContainedInSpatialStructure>& rel) {
                      for (const auto& e : rel->m_RelatedElements) {
                        if (!e) continue;
                        if (auto space = dynamic_pointer_cast<IfcSpace>(e)) {
                          if (std::find(spaces.begin(), spaces.end(), space) != spaces.end()) {
                            continue;
                          }
                          simplified(describe("space", space),
                                     "contained in its storey (IfcRelContainedInSpatialStructure) "
                                     "rather than aggregated (IfcRelAggregates): taken as a space "
                                     "of the storey");
                          spaces.push_back(space);
                          collectSpaces(space, spaces, 1);
                          continue;
                        }
                        record.elements.push_back(e);
                      }
                    });
    // Elements placed in a space belong to the space's storey.
    for (const auto& space : spaces) {
      record.spaces.push_back({space, footprintOf(bodies_.read(space).faces)});
      forEachRelation(space->m_ContainsElements_inverse,
                      [&](const shared_ptr<IfcRelContainedInSpatialStructure>& rel) {
                        for (const auto& e : rel->m_RelatedElements) {
                          if (e) record.elements.push_back(e);
                        }
                      });
    }
    // The floor people stand on is where the storey's rooms begin: IFC storey elevations are
    // sometimes the structural slab's, or a tool's reference level below it.
    std::vector<double> floors;
    for (const auto& space : record.spaces) {
      if (space.footprint) floors.push_back(space.footprint->z);
    }
    if (!floors.empty()) {
      std::nth_element(floors.begin(), floors.begin() + floors.size() / 2, floors.end());
      const double floor = floors[floors.size() / 2];
      if (std::abs(floor - record.elevation) > 0.01) {
        simplified("storey \"" + record.name + "\" " + record.global_id,
                   "its elevation is " + fmt(record.elevation) + " m, its spaces' floor " +
                       fmt(floor) + " m: the level's floor is taken where its rooms are");
        record.elevation = floor;
      }
    }
    storeys_.push_back(std::move(record));
  }
  if (storeys_.empty()) {
    throw common::InputError(file_, "", "no IfcBuildingStorey: the model has no storey to import");
  }
  std::stable_sort(
      storeys_.begin(), storeys_.end(),
      [](const StoreyRecord& a, const StoreyRecord& b) { return a.elevation < b.elevation; });
  // The first storey that contains an element is its storey (walls and columns look it up).
  for (int s = 0; s < int(storeys_.size()); ++s) {
    for (const auto& e : storeys_[s].elements) storey_of_.emplace(e.get(), s);
  }
}

std::optional<WallFit> Importer::wallFit(const shared_ptr<IfcElement>& element,
                                         const std::string& kind, const std::string& what) {
  Eigen::Matrix4d placement;
  const Mesh body = bodyWithParts(bodies_, element, &placement);
  const std::vector<std::string> non_positive = nonPositiveLengths(element);
  std::string lengths;
  for (const auto& n : non_positive) lengths += (lengths.empty() ? "" : ", ") + n;
  if (body.empty()) {
    dropped(what,
            "no body geometry IFC++ could build" +
                (lengths.empty() ? std::string()
                                 : " (IFC requires these lengths positive: " + lengths + ")"));
    return std::nullopt;
  }
  if (!lengths.empty()) {
    simplified(what, "IFC requires these lengths of its body positive: " + lengths +
                         "; IFC++ builds a negative one mirrored, and that body is used");
  }
  const Eigen::Vector2d own_x = placement.block<2, 1>(0, 0);
  const auto fit = fitWall(body, own_x);
  if (!fit || fit->thickness < bim::limits::kMinSize ||
      (fit->end - fit->start).norm() < bim::limits::kMinSize) {
    dropped(what, "its body has no extent seen from above");
    return std::nullopt;
  }
  if (fit->thickness > kMaxWallThickness) {
    dropped(what, "thicker than " + fmt(kMaxWallThickness) + " m seen from above (" +
                      fmt(fit->thickness) + " m): not one straight wall");
    return std::nullopt;
  }
  if (fit->straightness < kMinStraightness) {
    dropped(what, "not straight: seen from above it fills its " + fmt(fit->thickness) +
                      " m wide rectangle too little (straightness " +
                      std::to_string(int(std::round(fit->straightness * 100))) +
                      " %; an L-shaped or curved wall); the plan holds straight walls only");
    return std::nullopt;
  }
  // The rectangle covers more than the body: by a strip over kReportedChange wide, averaged
  // along the wall, when the ends are cut at an angle.
  if ((1.0 - fit->rectangle_fill) * (fit->end - fit->start).norm() > kReportedChange) {
    simplified(what, "its ends are not square (mitred or angled joints; it fills " +
                         std::to_string(int(std::round(fit->rectangle_fill * 100))) +
                         " % of its rectangle): taken as its rectangle, " +
                         fmt((fit->end - fit->start).norm()) + " m long");
  }
  if (fit->top - fit->bottom < bim::limits::kMinSize) {
    dropped(what, "no height left between its highest bottom and lowest top");
    return std::nullopt;
  }
  if (fit->highest_top - fit->top > kReportedChange) {
    simplified(what, "its top varies from " + fmt(fit->top) + " to " + fmt(fit->highest_top) +
                         " m (a gable or a sloped top): taken at its lowest, " + fmt(fit->top) +
                         " m, so that no wall stands where there is none");
  }
  if (fit->bottom - fit->lowest_bottom > kReportedChange) {
    simplified(what, "its bottom varies from " + fmt(fit->lowest_bottom) + " to " +
                         fmt(fit->bottom) + " m or more: taken at its median, " + fmt(fit->bottom) +
                         " m");
  }
  if (kind == "curtain wall") {
    simplified(what, "a curtain wall: imported as an opaque wall " + fmt(fit->thickness) +
                         " m thick (the simulated sensor does not see through glass)");
  }
  if (const auto layers = layerSetThickness(element, unit_)) {
    if (std::abs(*layers - fit->thickness) > kThicknessTolerance) {
      simplified(what, "its layer set is " + fmt(*layers) + " m thick, its body " +
                           fmt(fit->thickness) + " m: the body's thickness is kept");
    }
  }
  return fit;
}

void Importer::readWalls() {
  std::map<int, std::size_t> walls_in_storey;
  for (const auto& [id, entity] : loaded_.model->getMapIfcEntities()) {
    auto element = dynamic_pointer_cast<IfcElement>(entity);
    if (!element) continue;
    std::string kind;
    if (dynamic_pointer_cast<IfcWall>(entity)) {
      kind = "wall";
    } else if (dynamic_pointer_cast<IfcCurtainWall>(entity)) {
      kind = "curtain wall";
    } else {
      continue;
    }
    // A wall that is itself a part of a curtain wall (or another wall) is read with its whole.
    bool is_part = false;
    forEachRelation(element->m_Decomposes_inverse, [&](const shared_ptr<IfcRelAggregates>& rel) {
      if (dynamic_pointer_cast<IfcWall>(rel->m_RelatingObject) ||
          dynamic_pointer_cast<IfcCurtainWall>(rel->m_RelatingObject)) {
        is_part = true;
      }
    });
    if (is_part) continue;
    const std::string what = describe(kind, element);
    auto s = storey_of_.find(entity.get());
    if (s == storey_of_.end()) {
      dropped(what, "not contained in a building storey");
      continue;
    }
    const auto fit = wallFit(element, kind, what);
    if (!fit) continue;
    WallRecord wall;
    wall.element = element;
    wall.kind = kind;
    wall.global_id = globalIdOf(element);
    wall.name = labelText(element->m_Name);
    wall.storey = s->second;
    wall.fit = *fit;
    // Counted as they are read: a storey past the level's limit stops the import here, before
    // the rest of its walls are fitted.
    if (++walls_in_storey[wall.storey] > bim::limits::kMaxWallsPerLevel) {
      throw common::InputError(
          file_, "",
          "storey \"" + storeys_[std::size_t(wall.storey)].name + "\": more than " +
              std::to_string(bim::limits::kMaxWallsPerLevel) + " walls; at most " +
              std::to_string(bim::limits::kMaxWallsPerLevel) +
              " a level are supported (docs/formats.md, Limits)");
    }
    walls_.push_back(std::move(wall));
  }
}

void Importer::readColumns() {
  for (const auto& [id, entity] : loaded_.model->getMapIfcEntities()) {
    auto element = dynamic_pointer_cast<IfcColumn>(entity);
    if (!element) continue;
    const std::string what = describe("column", element);
    auto s = storey_of_.find(entity.get());
    if (s == storey_of_.end()) {
      dropped(what, "not contained in a building storey");
      continue;
    }
    Eigen::Matrix4d placement;
    const Mesh body = bodyWithParts(bodies_, element, &placement);
    const auto fit = body.empty() ? std::nullopt : fitWall(body, placement.block<2, 1>(0, 0));
    if (!fit || fit->thickness < bim::limits::kMinSize ||
        (fit->end - fit->start).norm() < bim::limits::kMinSize) {
      dropped(what, "no body geometry seen from above");
      continue;
    }
    ColumnRecord column;
    column.element = element;
    column.global_id = globalIdOf(element);
    column.name = labelText(element->m_Name);
    column.storey = s->second;
    column.fit = *fit;
    const Eigen::Vector2d along = fit->end - fit->start;
    const double length = along.norm();
    if (length > kMaxWallThickness || fit->thickness > kMaxWallThickness) {
      dropped(what, "wider than " + fmt(kMaxWallThickness) + " m seen from above (" + fmt(length) +
                        " × " + fmt(fit->thickness) + " m): not a column");
      continue;
    }
    if (fit->top - fit->bottom < bim::limits::kMinSize) {
      dropped(what, "no height left between its highest bottom and lowest top");
      continue;
    }
    column.center = 0.5 * (fit->start + fit->end);
    // A circle fills π/4 of its square (a polygon of 16 or more sides between 0.77 and 0.80): a
    // body whose rectangle is within 5 % of a square and which fills 0.74–0.82 of it is round.
    const double aspect = std::max(length, fit->thickness) / std::min(length, fit->thickness);
    if (aspect < 1.05 && fit->rectangle_fill > 0.74 && fit->rectangle_fill < 0.82) {
      column.round = true;
      const double d = 0.5 * (length + fit->thickness);
      column.size = {d, d};
    } else {
      column.size = {length, fit->thickness};
      column.yaw = std::atan2(along.y(), along.x());
      if (fit->rectangle_fill < 0.9) {
        simplified(what, "it fills " + std::to_string(int(std::round(fit->rectangle_fill * 100))) +
                             " % of its rectangle seen from above (a steel section or an "
                             "L-shaped column): taken as its rectangle, " +
                             fmt(length) + " × " + fmt(fit->thickness) + " m");
      }
    }
    columns_.push_back(std::move(column));
  }
}

bool Importer::fillsByPlace(const shared_ptr<IfcProduct>& element, const std::string& kind) {
  if (!element) return false;
  const Mesh body = bodies_.read(element).faces;
  if (body.empty()) return false;
  // The empty opening of an imported wall that the element's body lies in: its centre within the
  // wall's thickness of the wall's axis, and within the opening's extent along the wall.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (const auto& face : body) {
    for (const auto& p : face) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  for (auto& opening : openings_) {
    if (opening.kind != "opening") continue;
    const WallFit& fit = walls_[std::size_t(opening.wall)].fit;
    const Eigen::Vector2d axis = fit.end - fit.start;
    if (axis.norm() < 1e-9) continue;
    const Eigen::Vector2d u = axis.normalized();
    const Eigen::Vector2d d = centre.head<2>() - fit.start;
    const double along = d.dot(u), across = std::abs(d.x() * u.y() - d.y() * u.x());
    if (across > 0.5 * fit.thickness + 0.05 || along < opening.extent.along_min ||
        along > opening.extent.along_max || centre.z() < opening.extent.z_min ||
        centre.z() > opening.extent.z_max) {
      continue;
    }
    const auto root = dynamic_pointer_cast<IfcRoot>(element);
    simplified(describe(kind, root), "no IfcRelFillsElement names its opening: it fills opening " +
                                         opening.global_id + " of wall " +
                                         walls_[std::size_t(opening.wall)].global_id +
                                         ", in which it lies");
    opening.kind = kind;
    opening.described = root;
    opening.global_id = globalIdOf(root);
    opening.name = labelText(root->m_Name);
    return true;
  }
  return false;
}

void Importer::readOpenings() {
  std::set<BuildingEntity*> filled;  // doors and windows found in an opening
  for (int w = 0; w < int(walls_.size()); ++w) {
    const WallRecord& wall = walls_[w];
    forEachRelation(
        wall.element->m_HasOpenings_inverse, [&](const shared_ptr<IfcRelVoidsElement>& rel) {
          auto opening = dynamic_pointer_cast<IfcOpeningElement>(rel->m_RelatedOpeningElement);
          if (!opening) return;
          OpeningRecord record;
          record.wall = w;
          record.described = opening;
          forEachRelation(
              opening->m_HasFillings_inverse, [&](const shared_ptr<IfcRelFillsElement>& fill) {
                const auto& element = fill->m_RelatedBuildingElement;
                if (dynamic_pointer_cast<IfcDoor>(element)) {
                  record.kind = "door", record.described = element;
                } else if (dynamic_pointer_cast<IfcWindow>(element) && record.kind.empty()) {
                  record.kind = "window", record.described = element;
                }
                if (element) filled.insert(element.get());
              });
          const std::string what =
              describe(record.kind.empty() ? "opening" : record.kind, record.described) +
              " (in wall " + wall.global_id + ")";
          if (opening->m_PredefinedType &&
              opening->m_PredefinedType->m_enum == IfcOpeningElementTypeEnum::ENUM_RECESS) {
            dropped(what, "a recess, not an opening through the wall");
            return;
          }
          const Mesh body = bodies_.read(opening).faces;
          const auto extent = extentAlong(body, wall.fit.start, wall.fit.end);
          if (!extent) {
            dropped(what, "its opening has no body geometry");
            return;
          }
          record.extent = *extent;
          record.global_id = globalIdOf(record.described);
          record.name = labelText(record.described->m_Name);
          if (record.kind.empty()) record.kind = "opening";
          openings_.push_back(std::move(record));
        });
  }
  for (const auto& [id, entity] : loaded_.model->getMapIfcEntities()) {
    const bool door = dynamic_pointer_cast<IfcDoor>(entity) != nullptr;
    const bool window = dynamic_pointer_cast<IfcWindow>(entity) != nullptr;
    if ((!door && !window) || filled.count(entity.get())) continue;
    if (fillsByPlace(dynamic_pointer_cast<IfcProduct>(entity), door ? "door" : "window")) continue;
    dropped(describe(door ? "door" : "window", dynamic_pointer_cast<IfcRoot>(entity)),
            "it fills no opening of an imported wall (a partition or free-standing door, or its "
            "wall was left out)");
  }
}

void Importer::readFlights() {
  for (const auto& [id, entity] : loaded_.model->getMapIfcEntities()) {
    std::string kind;
    if (dynamic_pointer_cast<IfcStairFlight>(entity)) {
      kind = "stair flight";
    } else if (auto stair = dynamic_pointer_cast<IfcStair>(entity)) {
      // A stair is read through its flights when it has them (its landings are floor).
      bool has_flights = false;
      forEachRelation(stair->m_IsDecomposedBy_inverse, [&](const shared_ptr<IfcRelAggregates>& r) {
        for (const auto& part : r->m_RelatedObjects) {
          has_flights = has_flights || dynamic_pointer_cast<IfcStairFlight>(part) != nullptr;
        }
      });
      if (has_flights) continue;
      kind = "stair";
    } else {
      continue;
    }
    auto element = dynamic_pointer_cast<IfcProduct>(entity);
    const std::string what = describe(kind, element);
    const Mesh body = bodyWithParts(bodies_, element, nullptr);
    const auto fit = body.empty() ? std::nullopt : fitFlight(body);
    if (!fit) {
      dropped(what, "no body geometry IFC++ could build");
      continue;
    }
    flights_.push_back({element, kind, globalIdOf(element), labelText(element->m_Name), *fit});
  }
}

}  // namespace isg::ifc::importer
