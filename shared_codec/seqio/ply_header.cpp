// SPDX-License-Identifier: Apache-2.0
#include "seqio/ply_header.h"

#include <string_view>

#include "seqio/text_scan.h"

namespace animc {
namespace {

struct TypeName {
  const char* name;
  PlyType type;
};
constexpr TypeName kTypeNames[] = {
    {"char", PlyType::kInt8},      {"int8", PlyType::kInt8},       {"uchar", PlyType::kUint8},
    {"uint8", PlyType::kUint8},    {"short", PlyType::kInt16},     {"int16", PlyType::kInt16},
    {"ushort", PlyType::kUint16},  {"uint16", PlyType::kUint16},   {"int", PlyType::kInt32},
    {"int32", PlyType::kInt32},    {"uint", PlyType::kUint32},     {"uint32", PlyType::kUint32},
    {"float", PlyType::kFloat32},  {"float32", PlyType::kFloat32}, {"double", PlyType::kFloat64},
    {"float64", PlyType::kFloat64}};

bool typeFromName(std::string_view name, PlyType* type) {
  for (const TypeName& entry : kTypeNames) {
    if (name == entry.name) {
      *type = entry.type;
      return true;
    }
  }
  return false;
}

std::vector<std::string_view> splitWords(std::string_view line) {
  std::vector<std::string_view> words;
  TokenCursor cursor(line.data(), line.data() + line.size());
  std::string_view word;
  while (cursor.next(&word)) words.push_back(word);
  return words;
}

Status headerError(size_t line_number, const std::string& what) {
  return corrupt("PLY header line " + std::to_string(line_number) + ": " + what);
}

Status parseFormat(const std::vector<std::string_view>& words, size_t line, PlyHeader* header) {
  if (words.size() < 2) return headerError(line, "format line without a format");
  if (words[1] == "ascii")
    header->format = PlyFormat::kAscii;
  else if (words[1] == "binary_little_endian")
    header->format = PlyFormat::kBinaryLittleEndian;
  else if (words[1] == "binary_big_endian")
    header->format = PlyFormat::kBinaryBigEndian;
  else
    return headerError(line, "unknown format '" + std::string(words[1]) + "'");
  return Status();
}

Status parseElement(const std::vector<std::string_view>& words, size_t line, PlyHeader* header) {
  PlyElement element;
  if (words.size() != 3 || !parseUint64(words[2], &element.count))
    return headerError(line, "expected 'element <name> <count>'");
  element.name = std::string(words[1]);
  header->elements.push_back(std::move(element));
  return Status();
}

Status parseProperty(const std::vector<std::string_view>& words, size_t line, PlyHeader* header) {
  if (header->elements.empty()) return headerError(line, "property before any element");
  PlyProperty property;
  bool ok;
  if (words.size() >= 2 && words[1] == "list") {
    property.is_list = true;
    ok = words.size() == 5 && typeFromName(words[2], &property.count_type) &&
         typeFromName(words[3], &property.type) && plyTypeIsInteger(property.count_type);
  } else {
    ok = words.size() == 3 && typeFromName(words[1], &property.type);
  }
  if (!ok) return headerError(line, "unsupported property declaration");
  property.name = std::string(words.back());
  header->elements.back().properties.push_back(std::move(property));
  return Status();
}

}  // namespace

uint64_t plyMinInstanceBytes(const PlyElement& element, bool ascii) {
  uint64_t bytes = 0;
  for (const PlyProperty& p : element.properties)
    bytes += ascii ? 2 : plyTypeSize(p.is_list ? p.count_type : p.type);
  return bytes;
}

size_t plyTypeSize(PlyType type) {
  switch (type) {
    case PlyType::kInt8:
    case PlyType::kUint8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUint16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUint32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
  }
  return 1;
}

bool plyTypeIsInteger(PlyType type) {
  return type != PlyType::kFloat32 && type != PlyType::kFloat64;
}

Result<PlyHeader> parsePlyHeader(const uint8_t* data, size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  if (text.substr(0, 3) != "ply") return corrupt("not a PLY file (no 'ply' magic)");
  PlyHeader header;
  bool have_format = false;
  size_t pos = 0;
  for (size_t line_number = 1;; ++line_number) {
    size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) return truncated("PLY header has no end_header line");
    std::vector<std::string_view> words = splitWords(text.substr(pos, eol - pos));
    pos = eol + 1;
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
    if (line_number == 1) {
      if (words.size() != 1 || words[0] != "ply") return corrupt("not a PLY file (bad first line)");
    } else if (words[0] == "format") {
      ANIMC_RETURN_IF_ERROR(parseFormat(words, line_number, &header));
      have_format = true;
    } else if (words[0] == "element") {
      ANIMC_RETURN_IF_ERROR(parseElement(words, line_number, &header));
    } else if (words[0] == "property") {
      ANIMC_RETURN_IF_ERROR(parseProperty(words, line_number, &header));
    } else if (words[0] == "end_header") {
      break;
    } else {
      return headerError(line_number, "unknown keyword '" + std::string(words[0]) + "'");
    }
  }
  if (!have_format) return corrupt("PLY header has no format line");
  header.data_offset = pos;
  return header;
}

Status checkPlyDataSize(const PlyHeader& header, size_t data_size) {
  bool ascii = header.format == PlyFormat::kAscii;
  uint64_t budget = uint64_t(data_size) + (ascii ? 1 : 0);  // the last value needs no separator
  for (const PlyElement& element : header.elements) {
    uint64_t per_instance = plyMinInstanceBytes(element, ascii);
    if (per_instance == 0) continue;
    if (element.count > budget / per_instance)
      return truncated("header announces " + std::to_string(element.count) + " " + element.name +
                       " elements but only " + std::to_string(data_size) + " bytes of data follow");
    budget -= element.count * per_instance;
  }
  return Status();
}

}  // namespace animc
