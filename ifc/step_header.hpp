#pragma once

#include <cstddef>
#include <initializer_list>
#include <string>
#include <string_view>

namespace isg::ifc {

// What the import needs from an IFC-SPF (ISO 10303-21) file's text before any entity is read:
// the schema it claims and the authoring tool. Checking the text first gives the exact message a
// user needs — "not an IFC file", "truncated", "IFC4X3 is not supported" — where IFC++ would read
// a partial model silently.
struct StepHeader {
  std::string schema;       // "IFC2X3" or "IFC4"
  std::string application;  // FILE_NAME's originating system, "" when absent
};

// Throws common::InputError naming `file` when the text is not an ISO 10303-21 exchange file, has
// no FILE_SCHEMA, names a schema other than IFC2X3 and IFC4 (IFC4X1-IFC4X3, IFC2X2 …), or does
// not end with END-ISO-10303-21; (a truncated file).
StepHeader readStepHeader(const std::string& file, const std::string& text);

// A string left open (a quote missing) swallows the entity instances after it, which IFC++ then
// reads as nothing, unsaid. Throws common::InputError naming `file` and the line where such a
// string starts when a string runs past the end of its line into a line that starts a new entity
// instance ("#123="), or to the end of the file.
void checkStepStrings(const std::string& file, const std::string& text);

// How many entity instances of the given types ("IFCWALL", upper case) the text holds: each
// "= TYPE (" outside strings, the type's name in any case. One pass over the text, before IFC++
// reads a byte of it: limits are checked here rather than after the model is built.
std::size_t countInstances(const std::string& text, std::initializer_list<std::string_view> types);

}  // namespace isg::ifc
