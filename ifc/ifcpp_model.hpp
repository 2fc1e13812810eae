#pragma once

// The IFC++ side of the import (Debian's libifcplusplus-dev): reading the model and the bodies of
// its elements. Included only by this module's .cpp files: IFC++ puts its names in the global
// namespace and pulls in carve, which no user of the import should compile.

#include <ifcpp/IFC4/include/IfcLabel.h>
#include <ifcpp/IFC4/include/IfcProduct.h>
#include <ifcpp/model/BuildingModel.h>
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "ifc/mesh_fit.hpp"
#include "ifc/step_header.hpp"

class GeometryConverter;

namespace isg::ifc {

// IFC++ reports problems only through a callback: they are gathered here.
struct ReaderMessages {
  std::vector<std::string> errors;
};

struct LoadedModel {
  shared_ptr<BuildingModel> model;
  StepHeader header;
  ReaderMessages messages;
};

// Reads an IFC file's text (the caller read the file: IFC++'s own loadModelFromFile calls
// setlocale for the whole process). Throws common::InputError naming `file` for what the header
// check rejects and for a model without an IfcProject.
LoadedModel loadModel(const std::string& file, std::string text);

// IFC's text (IFC++ decodes it to wide strings) as UTF-8; "" for an absent label.
std::string utf8(const std::wstring& text);
std::string labelText(const shared_ptr<IfcLabel>& label);
std::string globalIdOf(const shared_ptr<IfcRoot>& object);

// An element's body without its openings subtracted (the import wants the wall's extent, and the
// openings as their own bodies), in the model's world coordinates in metres.
struct Body {
  Mesh faces;
  Eigen::Matrix4d placement = Eigen::Matrix4d::Identity();  // object placement, metres
};

// Lengths of the product's body that IFC requires positive (IfcPositiveLengthMeasure) but the file
// gives as zero or negative — an extrusion's Depth, a rectangle profile's XDim and YDim — each as
// "#77 IfcExtrudedAreaSolid Depth -3": IFC++ builds a negative one mirrored, so the body looks
// sound while the file is not; the import says so.
std::vector<std::string> nonPositiveLengths(const shared_ptr<IfcProduct>& product);

class BodyReader {
 public:
  explicit BodyReader(LoadedModel& model);
  ~BodyReader();
  BodyReader(const BodyReader&) = delete;
  BodyReader& operator=(const BodyReader&) = delete;

  Body read(const shared_ptr<IfcProduct>& product);
  // The placement alone (a storey has no body).
  Eigen::Matrix4d placementOf(const shared_ptr<IfcProduct>& product);
  double metresPerUnit() const;

 private:
  LoadedModel& model_;
  std::unique_ptr<GeometryConverter> converter_;
};

}  // namespace isg::ifc
