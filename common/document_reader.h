// The one reading path for YAML and JSON documents (scenes, law files, pipeline files,
// manifests): every stage parses through here, so hostile or broken files get the same
// treatment everywhere. On top of syntax, a document is rejected (InputError naming the file,
// the key path and the reason; nothing is written) when
//   - its size exceeds max_document_bytes, or it is not a readable regular file;
//   - it contains bytes that are not UTF-8 (also strings made of escapes such as "\xff");
//   - it nests deeper than max_document_depth mappings/lists (deep nesting used to overflow
//     the stack: recursive copies and dumps of nlohmann::json);
//   - after YAML aliases are expanded it has more than 4 values per byte of text (+ 10⁴) or
//     more than max_document_nodes values (an alias bomb would otherwise exhaust memory);
//   - a number overflows a double (1e400) — YAML's .inf/.nan and the words inf/nan are not
//     numbers here, so a numeric key given one of them is rejected by its range check;
//   - a mapping has the same key twice (the earlier value would be silently ignored);
//   - a YAML file holds more than one document ('---' separators), whose rest would be ignored.
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>

namespace clearjoint
{
  /// The deepest shipped document nests 4 levels; 64 leaves room for any hand-written file while
  /// keeping every recursive walk over a document far from the stack limit.
  inline constexpr int max_document_depth = 64;
  /// The largest shipped document has a few hundred values; 10⁶ allows generated law tables.
  inline constexpr std::size_t max_document_nodes = 1'000'000;
  /// 64 MiB: far above any scene, law or pipeline file; protects against /dev/zero and the like.
  inline constexpr std::size_t max_document_bytes = 64u << 20;

  /// Parses a file into JSON (by extension: .json → JSON, anything else → YAML).
  nlohmann::json read_structured_file(const std::string &path);
  nlohmann::json read_json_file(const std::string &path);
  nlohmann::json read_yaml_file(const std::string &path);
  /// source_name is used in messages in place of a file name.
  nlohmann::json parse_json_string(const std::string &text, const std::string &source_name);
  nlohmann::json parse_yaml_string(const std::string &text, const std::string &source_name);

  /// Reads a whole input file of at most max_bytes; InputError naming the file if it is not a
  /// readable regular file or is larger.
  std::string read_input_file(const std::string &path,
                              std::size_t max_bytes = max_document_bytes);

  /// Offset of the first byte that is not part of well-formed UTF-8 (overlong forms,
  /// surrogates and code points above U+10FFFF included), or std::string::npos.
  std::size_t first_invalid_utf8(const std::string &text);

  /// A document as text for a file (indent as nlohmann's dump): never throws on strings that
  /// are not UTF-8 — paths from the command line or the working directory may hold any byte
  /// (a folder named with 0xFF); such bytes are written as U+FFFD rather than the stage
  /// aborting on its last write.
  std::string json_text(const nlohmann::json &value, int indent = 2);

  /// A value as short text for messages: never throws (invalid UTF-8 replaced), at most
  /// max_chars characters ("..." appended when cut).
  std::string json_excerpt(const nlohmann::json &value, std::size_t max_chars = 120);
} // namespace clearjoint
