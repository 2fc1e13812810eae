#include <ifcpp/IFC4/include/IfcExtrudedAreaSolid.h>
#include <ifcpp/IFC4/include/IfcGloballyUniqueId.h>
#include <ifcpp/IFC4/include/IfcPositiveLengthMeasure.h>
#include <ifcpp/IFC4/include/IfcProductRepresentation.h>
#include <ifcpp/IFC4/include/IfcProject.h>
#include <ifcpp/IFC4/include/IfcRectangleProfileDef.h>
#include <ifcpp/IFC4/include/IfcRepresentation.h>
#include <ifcpp/geometry/Carve/GeometryConverter.h>
#include <ifcpp/reader/ReaderSTEP.h>

#include <cctype>
#include <cstdio>
#include <unordered_set>

#include "common/input_error.hpp"
#include "common/untracked_allocations.hpp"
#include "ifc/ifcpp_model.hpp"

namespace isg::ifc {
namespace {

void gatherMessage(void* target, shared_ptr<StatusCallback::Message> message) {
  auto* messages = static_cast<ReaderMessages*>(target);
  if (!message || message->m_message_type != StatusCallback::MESSAGE_TYPE_ERROR) return;
  // One line per problem (IFC++ joins several into one message).
  std::string text = utf8(message->m_message_text);
  std::size_t begin = 0;
  while (begin < text.size() && messages->errors.size() < 1000) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(begin, end - begin);
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
    if (!line.empty()) messages->errors.push_back(line);
    begin = end + 1;
  }
}

// Representations that are not the element's body.
bool isBody(const shared_ptr<IfcRepresentation>& representation) {
  if (!representation) return false;
  const std::string id = labelText(representation->m_RepresentationIdentifier);
  static const std::unordered_set<std::string> not_body{
      "Axis",      "Box", "FootPrint", "Annotation", "Profile", "Reference",
      "Clearance", "CoG", "Lighting",  "Surface",    "Plan"};
  return not_body.count(id) == 0;
}

Eigen::Matrix4d toEigen(const carve::math::Matrix& m) {
  Eigen::Matrix4d e;
  // carve's Matrix is column-major: m[column][row].
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) e(r, c) = m.m[c][r];
  }
  return e;
}

void appendMeshSet(const carve::mesh::MeshSet<3>& mesh_set, const carve::math::Matrix& transform,
                   Mesh& out) {
  for (const auto* mesh : mesh_set.meshes) {
    for (const auto* face : mesh->faces) {
      Face polygon;
      const auto* edge = face->edge;
      if (edge == nullptr) continue;
      std::size_t guard = 0;
      do {
        const carve::geom::vector<3> p = transform * edge->vert->v;
        polygon.emplace_back(p.x, p.y, p.z);
        edge = edge->next;
      } while (edge != face->edge && ++guard < 100000);
      if (polygon.size() >= 3) out.push_back(std::move(polygon));
    }
  }
}

}  // namespace

std::string utf8(const std::wstring& text) {
  std::string out;
  out.reserve(text.size());
  for (const wchar_t wc : text) {
    auto c = static_cast<std::uint32_t>(wc);
    if (c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF)) c = 0xFFFD;
    if (c < 0x80) {
      out += static_cast<char>(c);
    } else if (c < 0x800) {
      out += static_cast<char>(0xC0 | (c >> 6));
      out += static_cast<char>(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
      out += static_cast<char>(0xE0 | (c >> 12));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (c & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (c >> 18));
      out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (c & 0x3F));
    }
  }
  return out;
}

std::string labelText(const shared_ptr<IfcLabel>& label) {
  return label ? utf8(label->m_value) : "";
}

std::string globalIdOf(const shared_ptr<IfcRoot>& object) {
  return object && object->m_GlobalId ? utf8(object->m_GlobalId->m_value) : "";
}

LoadedModel loadModel(const std::string& file, std::string text) {
  LoadedModel loaded;
  loaded.header = readStepHeader(file, text);
  loaded.model = std::make_shared<BuildingModel>();
  ReaderSTEP reader;
  reader.setMessageCallBack(&loaded.messages, &gatherMessage);
  loaded.model->setMessageCallBack(&loaded.messages, &gatherMessage);
  try {
    // IFC++'s reader leaks on malformed files (bim/untracked_allocations.hpp).
    const common::UntrackedAllocations untracked;
    reader.loadModelFromString(text, loaded.model);
  } catch (const std::exception& e) {
    throw common::InputError(file, "", std::string("IFC++ could not read the model: ") + e.what());
  }
  if (!loaded.model->getIfcProject()) {
    std::string why = loaded.messages.errors.empty() ? "" : " (" + loaded.messages.errors[0] + ")";
    throw common::InputError(file, "", "no IfcProject: not a readable IFC model" + why);
  }
  return loaded;
}

BodyReader::BodyReader(LoadedModel& model) : model_(model) {
  converter_ = std::make_unique<GeometryConverter>(model_.model);
  converter_->setMessageCallBack(&model_.messages, &gatherMessage);
  converter_->getRepresentationConverter()->setMessageCallBack(&model_.messages, &gatherMessage);
}

BodyReader::~BodyReader() = default;

double BodyReader::metresPerUnit() const {
  return model_.model->getUnitConverter()->getLengthInMeterFactor();
}

Eigen::Matrix4d BodyReader::placementOf(const shared_ptr<IfcProduct>& product) {
  auto shape = std::make_shared<ProductShapeData>(product->m_entity_id);
  std::unordered_set<IfcObjectPlacement*> applied;
  if (product->m_ObjectPlacement) {
    converter_->getRepresentationConverter()->getPlacementConverter()->convertIfcObjectPlacement(
        product->m_ObjectPlacement, shape, applied, false);
  }
  return toEigen(shape->getTransform());
}

std::vector<std::string> nonPositiveLengths(const shared_ptr<IfcProduct>& product) {
  std::vector<std::string> found;
  const auto check = [&](const BuildingEntity& owner, const char* type, const char* attribute,
                         const shared_ptr<IfcPositiveLengthMeasure>& length) {
    if (!length || length->m_value > 0) return;
    char value[32];
    std::snprintf(value, sizeof value, "%g", length->m_value);
    found.push_back("#" + std::to_string(owner.m_entity_id) + " " + type + " " + attribute + " " +
                    value);
  };
  if (!product || !product->m_Representation) return found;
  for (const auto& representation : product->m_Representation->m_Representations) {
    if (!isBody(representation)) continue;
    for (const auto& item : representation->m_Items) {
      const auto solid = dynamic_pointer_cast<IfcExtrudedAreaSolid>(item);
      if (!solid) continue;
      check(*solid, "IfcExtrudedAreaSolid", "Depth", solid->m_Depth);
      if (const auto rectangle = dynamic_pointer_cast<IfcRectangleProfileDef>(solid->m_SweptArea)) {
        check(*rectangle, "IfcRectangleProfileDef", "XDim", rectangle->m_XDim);
        check(*rectangle, "IfcRectangleProfileDef", "YDim", rectangle->m_YDim);
      }
    }
  }
  return found;
}

Body BodyReader::read(const shared_ptr<IfcProduct>& product) {
  Body body;
  auto shape = std::make_shared<ProductShapeData>(product->m_entity_id);
  shape->m_ifc_object_definition = product;
  if (product->m_Representation) {
    for (const auto& representation : product->m_Representation->m_Representations) {
      if (!isBody(representation)) continue;
      auto data = std::make_shared<RepresentationData>();
      try {
        // IFC++ leaks carve's CSG collector of each boolean operation (a bug of the library:
        // bim/untracked_allocations.hpp).
        const common::UntrackedAllocations untracked;
        converter_->getRepresentationConverter()->convertIfcRepresentation(representation, data);
      } catch (const std::exception& e) {
        model_.messages.errors.push_back(e.what());
        continue;
      }
      shape->m_vec_representations.push_back(data);
    }
  }
  std::unordered_set<IfcObjectPlacement*> applied;
  if (product->m_ObjectPlacement) {
    converter_->getRepresentationConverter()->getPlacementConverter()->convertIfcObjectPlacement(
        product->m_ObjectPlacement, shape, applied, false);
  }
  const carve::math::Matrix transform = shape->getTransform();
  body.placement = toEigen(transform);
  for (const auto& representation : shape->m_vec_representations) {
    for (const auto& item : representation->m_vec_item_data) {
      for (const auto& mesh_set : item->m_meshsets) appendMeshSet(*mesh_set, transform, body.faces);
      for (const auto& mesh_set : item->m_meshsets_open) {
        appendMeshSet(*mesh_set, transform, body.faces);
      }
    }
  }
  return body;
}

}  // namespace isg::ifc
