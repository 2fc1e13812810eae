#include "ifc/step_header.hpp"

#include <algorithm>
#include <cctype>
#include <vector>

#include "common/input_error.hpp"

namespace isg::ifc {
namespace {

// The header section, where FILE_NAME and FILE_SCHEMA live, upper-cased for the keywords; bounded
// so that a huge file without one is not searched to its end.
std::string headerSection(const std::string& text) {
  const std::size_t end = text.find("ENDSEC;");
  return text.substr(0,
                     std::min<std::size_t>(end == std::string::npos ? text.size() : end, 1 << 16));
}

std::string trimmedTail(const std::string& text) {
  std::size_t end = text.size();
  while (end > 0 && std::isspace(static_cast<unsigned char>(text[end - 1]))) --end;
  const std::size_t begin = end > 64 ? end - 64 : 0;
  return text.substr(begin, end - begin);
}

std::string upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::toupper(c); });
  return s;
}

// The arguments of the STEP record `keyword(...)` at top level, strings unquoted ('' → '),
// lists and other values as their text. Empty when the keyword or its parenthesis is missing.
std::vector<std::string> recordArguments(const std::string& header, const std::string& keyword) {
  const std::size_t at = upper(header).find(keyword);
  if (at == std::string::npos) return {};
  std::size_t i = at + keyword.size();
  while (i < header.size() && std::isspace(static_cast<unsigned char>(header[i]))) ++i;
  if (i >= header.size() || header[i] != '(') return {};
  std::vector<std::string> arguments(1);
  int depth = 0;
  for (++i; i < header.size(); ++i) {
    const char c = header[i];
    if (c == '\'') {
      // A string: '' inside it is one quote.
      for (++i; i < header.size(); ++i) {
        if (header[i] == '\'') {
          if (i + 1 < header.size() && header[i + 1] == '\'') {
            arguments.back() += '\'';
            ++i;
            continue;
          }
          break;
        }
        if (depth == 0) arguments.back() += header[i];
      }
      continue;
    }
    if (c == '(') {
      ++depth;
    } else if (c == ')') {
      if (depth == 0) return arguments;
      --depth;
    } else if (c == ',' && depth == 0) {
      arguments.emplace_back();
    } else if (depth == 0 && !std::isspace(static_cast<unsigned char>(c))) {
      arguments.back() += c;
    }
  }
  return {};  // not closed
}

// The first string of FILE_SCHEMA's list.
std::string firstSchema(const std::string& header) {
  const std::size_t at = upper(header).find("FILE_SCHEMA");
  if (at == std::string::npos) return "";
  const std::size_t open = header.find('\'', at);
  if (open == std::string::npos) return "";
  const std::size_t close = header.find('\'', open + 1);
  if (close == std::string::npos) return "";
  for (std::size_t i = at + 11; i < open; ++i) {
    const char c = header[i];
    if (c != '(' && !std::isspace(static_cast<unsigned char>(c))) return "";
  }
  return header.substr(open + 1, close - open - 1);
}

}  // namespace

StepHeader readStepHeader(const std::string& file, const std::string& text) {
  std::size_t first = 0;
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) first = 3;  // a UTF-8 byte order mark
  while (first < text.size() && std::isspace(static_cast<unsigned char>(text[first]))) ++first;
  if (text.compare(first, 13, "ISO-10303-21;") != 0) {
    throw common::InputError(file, "",
                             "not an IFC file: an IFC (STEP, ISO 10303-21) file starts with "
                             "\"ISO-10303-21;\"");
  }
  const std::string header = headerSection(text);
  const std::string schema_text = firstSchema(header);
  if (schema_text.empty()) {
    throw common::InputError(file, "",
                             "no FILE_SCHEMA in the file's header: which IFC schema it "
                             "follows is unknown");
  }
  const std::string schema = upper(schema_text);
  StepHeader result;
  if (schema == "IFC2X3" || schema == "IFC4") {
    result.schema = schema;
  } else {
    throw common::InputError(file, "",
                             "schema " + schema_text +
                                 " is not supported: the import reads IFC2X3 and IFC4 (export the "
                                 "model as one of them)");
  }
  if (trimmedTail(text).find("END-ISO-10303-21;") == std::string::npos) {
    throw common::InputError(file, "",
                             "truncated: the file does not end with \"END-ISO-10303-21;\"");
  }
  // FILE_NAME(name, time_stamp, author, organization, preprocessor_version, originating_system,
  // authorization): the sixth is the tool that made the model.
  const std::vector<std::string> file_name = recordArguments(header, "FILE_NAME");
  // Tools differ in which of preprocessor_version and originating_system names them: both.
  for (std::size_t i = 4; i < std::min<std::size_t>(file_name.size(), 6); ++i) {
    if (file_name[i].empty() || file_name[i] == "$") continue;
    result.application += (result.application.empty() ? "" : " / ") + file_name[i];
  }
  return result;
}

void checkStepStrings(const std::string& file, const std::string& text) {
  const std::size_t data = text.find("DATA;");
  if (data == std::string::npos) return;
  const auto line_of = [&](std::size_t at) {
    return std::size_t(std::count(text.begin(), text.begin() + std::ptrdiff_t(at), '\n')) + 1;
  };
  const auto fail = [&](std::size_t opened, const std::string& why) {
    std::size_t end = opened + 1;
    while (end < text.size() && end < opened + 41 && text[end] != '\n' && text[end] != '\r') ++end;
    throw common::InputError(file, "",
                             "line " + std::to_string(line_of(opened)) + ": the string " +
                                 text.substr(opened, end - opened) + "… is never closed: " + why +
                                 " (a quote is missing)");
  };
  bool in_string = false;
  std::size_t opened = 0;
  for (std::size_t i = data; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\'') {
      if (!in_string) opened = i;
      in_string = !in_string;  // '' inside a string closes and reopens it
      continue;
    }
    if (!in_string || c != '\n') continue;
    std::size_t k = i + 1;
    while (k < text.size() && (text[k] == ' ' || text[k] == '\t' || text[k] == '\r')) ++k;
    if (k >= text.size() || text[k] != '#') continue;
    std::size_t digits = k + 1;
    while (digits < text.size() && std::isdigit(static_cast<unsigned char>(text[digits]))) ++digits;
    while (digits < text.size() && text[digits] == ' ') ++digits;
    if (digits > k + 1 && digits < text.size() && text[digits] == '=') {
      fail(opened, "it runs into the entity instance on line " + std::to_string(line_of(k)));
    }
  }
  if (in_string) fail(opened, "the file ends inside it");
}

std::size_t countInstances(const std::string& text, std::initializer_list<std::string_view> types) {
  std::size_t count = 0;
  bool in_string = false;
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n; ++i) {
    const char c = text[i];
    if (c == '\'') {
      in_string = !in_string;  // '' inside a string closes and reopens it: the same state after
      continue;
    }
    if (in_string || c != '=') continue;
    std::size_t at = i + 1;
    while (at < n && std::isspace(static_cast<unsigned char>(text[at]))) ++at;
    std::size_t end = at;
    while (end < n && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '_')) {
      ++end;
    }
    std::size_t open = end;
    while (open < n && std::isspace(static_cast<unsigned char>(text[open]))) ++open;
    if (end == at || open >= n || text[open] != '(') continue;
    for (const std::string_view type : types) {
      if (type.size() != end - at) continue;
      bool same = true;
      for (std::size_t k = 0; k < type.size() && same; ++k) {
        same = std::toupper(static_cast<unsigned char>(text[at + k])) == type[k];
      }
      if (same) {
        ++count;
        break;
      }
    }
    i = open;
  }
  return count;
}

}  // namespace isg::ifc
