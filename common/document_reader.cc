#include "common/document_reader.h"

#include "common/error.h"

#include <yaml-cpp/depthguard.h>  // YAML::DeepRecursion
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace clearjoint
{
  namespace
  {
    using json = nlohmann::json;

    /// "line L, column C" (1-based) of a byte offset, for messages.
    std::string position_of(const std::string &text, const std::size_t offset)
    {
      std::size_t line = 1, column = 1;
      for (std::size_t i = 0; i < offset && i < text.size(); ++i)
      {
        if (text[i] == '\n')
        {
          ++line;
          column = 1;
        }
        else
          ++column;
      }
      return "line " + std::to_string(line) + ", column " + std::to_string(column);
    }

    void check_utf8(const std::string &text, const std::string &source)
    {
      const std::size_t bad = first_invalid_utf8(text);
      if (bad != std::string::npos)
      {
        char byte[8];
        std::snprintf(byte, sizeof(byte), "0x%02X", static_cast<unsigned char>(text[bad]));
        throw InputError(source, "", byte, "UTF-8 text",
                         "byte at " + position_of(text, bad) + " is not valid UTF-8");
      }
    }

    std::string child_path(const std::string &parent, const std::string &key)
    {
      return parent.empty() ? key : parent + "." + key;
    }

    std::string index_path(const std::string &parent, const std::size_t i)
    {
      return (parent.empty() ? "(top level)" : parent) + "[" + std::to_string(i) + "]";
    }

    [[noreturn]] void too_deep(const std::string &source, const std::string &path)
    {
      throw InputError(source, path.empty() ? "(top level)" : path, "(nested mappings/lists)",
                       "at most " + std::to_string(max_document_depth) + " levels of nesting");
    }

    [[noreturn]] void duplicate_key(const std::string &source, const std::string &path,
                                    const std::string &where)
    {
      throw InputError(source, path, "(given twice)", "each key at most once per mapping",
                       "duplicate key" + where + "; the earlier value would be silently ignored");
    }

    // ---------------------------------------------------------------- JSON
    /// Builds the document from nlohmann's SAX events, so the key path is known at every
    /// event: depth, duplicate keys and overflowing numbers are reported where they occur.
    class JsonBuilder
    {
    public:
      using number_integer_t = json::number_integer_t;
      using number_unsigned_t = json::number_unsigned_t;
      using number_float_t = json::number_float_t;
      using string_t = json::string_t;
      using binary_t = json::binary_t;

      JsonBuilder(const std::string &text, const std::string &source)
        : text_(text)
        , source_(source)
      {}

      bool null() { return put(nullptr); }
      bool boolean(const bool b) { return put(b); }
      bool number_integer(const number_integer_t v) { return put(v); }
      bool number_unsigned(const number_unsigned_t v) { return put(v); }
      bool number_float(const number_float_t v, const string_t &literal)
      {
        if (!std::isfinite(v))  // nlohmann reports overflow through parse_error; be sure anyway
          throw InputError(source_, value_path(), literal, "a finite number",
                           "the number does not fit in a double");
        return put(v);
      }
      bool string(string_t &s) { return put(std::move(s)); }
      bool binary(binary_t &) { return put(nullptr); }  // not produced by the JSON lexer
      bool start_object(std::size_t) { return open(json::object()); }
      bool start_array(std::size_t) { return open(json::array()); }
      bool end_object() { return close(); }
      bool end_array() { return close(); }
      bool key(string_t &k)
      {
        if (stack_.back()->contains(k))
          duplicate_key(source_, child_path(paths_.back(), k), "");
        key_ = std::move(k);
        return true;
      }
      bool parse_error(const std::size_t position, const std::string &token,
                       const nlohmann::detail::exception &e)
      {
        if (e.id == 406)  // out_of_range.406: number overflow
          throw InputError(source_, value_path(), token, "a finite number",
                           "the number does not fit in a double, at " +
                             position_of(text_, position == 0 ? 0 : position - 1));
        // nlohmann's message already names line and column; drop its "[json.exception...] ".
        std::string what = e.what();
        const auto cut = what.find("] ");
        if (cut != std::string::npos)
          what = what.substr(cut + 2);
        throw InputError("malformed JSON in '" + source_ + "': " + what);
      }

      json release() { return std::move(root_); }

    private:
      /// Path of the value about to be stored.
      std::string value_path() const
      {
        if (stack_.empty())
          return "(top level)";
        const json &top = *stack_.back();
        return top.is_object() ? child_path(paths_.back(), key_)
                               : index_path(paths_.back(), top.size());
      }

      json *store(json &&v)
      {
        if (++n_values_ > max_document_nodes)
          throw InputError(source_, value_path(), "(too many values)",
                           "at most " + std::to_string(max_document_nodes) + " values");
        if (stack_.empty())
        {
          root_ = std::move(v);
          return &root_;
        }
        json &top = *stack_.back();
        if (top.is_object())
          return &(top[key_] = std::move(v));
        top.push_back(std::move(v));
        return &top.back();
      }

      bool put(json &&v)
      {
        store(std::move(v));
        return true;
      }

      bool open(json &&container)
      {
        const std::string path = value_path();
        if (static_cast<int>(stack_.size()) >= max_document_depth)
          too_deep(source_, path);
        // Pointers stay valid: nothing is added to a parent while its child is open.
        stack_.push_back(store(std::move(container)));
        paths_.push_back(stack_.size() == 1 ? "" : path);
        return true;
      }

      bool close()
      {
        stack_.pop_back();
        paths_.pop_back();
        return true;
      }

      const std::string &text_;
      const std::string &source_;
      json root_;
      std::vector<json *> stack_;
      std::vector<std::string> paths_;  // key path of each open container
      std::string key_;
      std::size_t n_values_ = 0;
    };

    // ---------------------------------------------------------------- YAML
    /// A plain scalar is a number only if it is written as one: [-+]digits[.digits][e[-+]digits]
    /// (also ".5" and "5."). Words such as inf, nan, .inf, 0x10 stay strings.
    bool looks_numeric(const std::string &s, bool &is_integer)
    {
      std::size_t i = 0;
      if (i < s.size() && (s[i] == '+' || s[i] == '-'))
        ++i;
      std::size_t digits = 0;
      while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])))
        ++i, ++digits;
      is_integer = true;
      if (i < s.size() && s[i] == '.')
      {
        is_integer = false;
        ++i;
        while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])))
          ++i, ++digits;
      }
      if (digits == 0)
        return false;
      if (i < s.size() && (s[i] == 'e' || s[i] == 'E'))
      {
        is_integer = false;
        ++i;
        if (i < s.size() && (s[i] == '+' || s[i] == '-'))
          ++i;
        std::size_t exp_digits = 0;
        while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])))
          ++i, ++exp_digits;
        if (exp_digits == 0)
          return false;
      }
      return i == s.size();
    }

    /// The first pass over a YAML text (see parse_yaml_string): counts documents and follows
    /// the key path of every node from the parser's events, so that nesting deeper than
    /// max_document_depth is reported with its key path before yaml-cpp builds the tree.
    class DocumentScanner : public YAML::EventHandler
    {
    public:
      explicit DocumentScanner(const std::string &source)
        : source_(source)
      {}

      void OnDocumentStart(const YAML::Mark &) override { stack_.clear(); }
      void OnDocumentEnd() override {}
      void OnNull(const YAML::Mark &, YAML::anchor_t) override { node_done(nullptr); }
      void OnAlias(const YAML::Mark &, YAML::anchor_t) override { node_done(nullptr); }
      void OnScalar(const YAML::Mark &, const std::string &, YAML::anchor_t,
                    const std::string &value) override
      {
        node_done(&value);
      }
      void OnSequenceStart(const YAML::Mark &, const std::string &, YAML::anchor_t,
                           YAML::EmitterStyle::value) override
      {
        open(false);
      }
      void OnSequenceEnd() override { close(); }
      void OnMapStart(const YAML::Mark &, const std::string &, YAML::anchor_t,
                      YAML::EmitterStyle::value) override
      {
        open(true);
      }
      void OnMapEnd() override { close(); }

    private:
      struct Frame
      {
        bool map;
        bool expect_key;
        std::string key;      // the key whose value comes next (maps)
        std::size_t index;    // the index of the next element (lists)
        std::string path;     // this container's key path
      };

      /// Key path of the node about to start.
      std::string next_path() const
      {
        if (stack_.empty())
          return "";
        const Frame &f = stack_.back();
        if (f.map)
          return child_path(f.path, f.expect_key ? "(key)" : f.key);
        return index_path(f.path, f.index);
      }

      void open(const bool map)
      {
        const std::string path = next_path();
        if (static_cast<int>(stack_.size()) >= max_document_depth)
          too_deep(source_, path);
        stack_.push_back({map, true, "", 0, path});
      }

      void close()
      {
        if (!stack_.empty())
          stack_.pop_back();
        node_done(nullptr);
      }

      /// A node ended: a key (its text, if a scalar) or a value.
      void node_done(const std::string *scalar)
      {
        if (stack_.empty())
          return;
        Frame &f = stack_.back();
        if (!f.map)
          ++f.index;
        else if (f.expect_key)
        {
          f.key = scalar ? *scalar : "(key)";
          f.expect_key = false;
        }
        else
          f.expect_key = true;
      }

      const std::string &source_;
      std::vector<Frame> stack_;
    };

    class YamlConverter
    {
    public:
      /// Without aliases a document has fewer values than bytes; aliases may repeat parts, but
      /// more than 4 values per byte (+ 10⁴) is an alias bomb, stopped long before
      /// max_document_nodes would be reached (which takes seconds).
      YamlConverter(const std::string &source, const std::size_t text_size)
        : source_(source)
        , max_values_(std::min(max_document_nodes, 4 * text_size + 10'000))
      {}

      json convert(const YAML::Node &node, const std::string &path, const int depth)
      {
        if (++n_values_ > max_values_)
          throw InputError(source_, path.empty() ? "(top level)" : path, "(too many values)",
                           "at most " + std::to_string(max_values_) +
                             " values after YAML aliases are expanded (4 per byte of the "
                             "file, at most " + std::to_string(max_document_nodes) + ")");
        switch (node.Type())
        {
          case YAML::NodeType::Null:
          case YAML::NodeType::Undefined:
            return nullptr;
          case YAML::NodeType::Scalar:
            return scalar(node, path);
          case YAML::NodeType::Sequence:
          {
            if (depth >= max_document_depth)
              too_deep(source_, path);
            json a = json::array();
            std::size_t i = 0;
            for (const auto &e : node)
            {
              a.push_back(convert(e, index_path(path, i), depth + 1));
              ++i;
            }
            return a;
          }
          case YAML::NodeType::Map:
          {
            if (depth >= max_document_depth)
              too_deep(source_, path);
            json o = json::object();
            for (const auto &kv : node)
            {
              if (!kv.first.IsScalar())
                throw InputError(source_, path.empty() ? "(top level)" : path,
                                 "(a key that is a list or mapping)", "plain text keys",
                                 "at line " + std::to_string(kv.first.Mark().line + 1));
              const std::string key = kv.first.Scalar();
              check_string(key, child_path(path, "(key)"));
              if (o.contains(key))
                duplicate_key(source_, child_path(path, key),
                              " at line " + std::to_string(kv.first.Mark().line + 1));
              o[key] = convert(kv.second, child_path(path, key), depth + 1);
            }
            return o;
          }
        }
        return nullptr;
      }

    private:
      void check_string(const std::string &s, const std::string &path) const
      {
        // The file's bytes were checked; escapes in double-quoted scalars can still make bytes
        // that are not UTF-8 ("\xff").
        if (first_invalid_utf8(s) != std::string::npos)
          throw InputError(source_, path, "(text with an escape that is not UTF-8)",
                           "UTF-8 text");
      }

      json scalar(const YAML::Node &node, const std::string &path) const
      {
        const std::string &s = node.Scalar();
        check_string(s, path);
        // Quoted scalars ("!") and explicit !!str tags are always strings.
        if (node.Tag() == "!" || node.Tag() == "tag:yaml.org,2002:str")
          return s;
        if (s == "true" || s == "True" || s == "TRUE")
          return true;
        if (s == "false" || s == "False" || s == "FALSE")
          return false;
        if (s == "~" || s == "null" || s == "Null" || s == "NULL" || s.empty())
          return nullptr;
        bool is_integer = false;
        if (!looks_numeric(s, is_integer))
          return s;
        if (is_integer)
        {
          errno = 0;
          const long long i = std::strtoll(s.c_str(), nullptr, 10);
          if (errno == 0)
            return i;
          // Too large for a 64-bit integer: read it as a double below.
        }
        errno = 0;
        const double d = std::strtod(s.c_str(), nullptr);
        if (!std::isfinite(d) || (errno == ERANGE && std::fabs(d) > 1.0))
          throw InputError(source_, path.empty() ? "(top level)" : path, s, "a finite number",
                           "the number does not fit in a double, at line " +
                             std::to_string(node.Mark().line + 1));
        return d;  // underflow (1e-400) gives 0 or a subnormal; range checks judge it
      }

      const std::string &source_;
      std::size_t max_values_;
      std::size_t n_values_ = 0;
    };
  } // namespace

  std::size_t first_invalid_utf8(const std::string &text)
  {
    const auto *p = reinterpret_cast<const unsigned char *>(text.data());
    const std::size_t n = text.size();
    std::size_t i = 0;
    while (i < n)
    {
      const unsigned char c = p[i];
      if (c < 0x80)
      {
        ++i;
        continue;
      }
      std::size_t len;
      unsigned lo = 0x80, hi = 0xBF;  // allowed range of the second byte (RFC 3629 table)
      if (c >= 0xC2 && c <= 0xDF)
        len = 2;
      else if (c >= 0xE0 && c <= 0xEF)
      {
        len = 3;
        if (c == 0xE0)
          lo = 0xA0;  // no overlong forms
        if (c == 0xED)
          hi = 0x9F;  // no surrogates
      }
      else if (c >= 0xF0 && c <= 0xF4)
      {
        len = 4;
        if (c == 0xF0)
          lo = 0x90;
        if (c == 0xF4)
          hi = 0x8F;  // nothing above U+10FFFF
      }
      else
        return i;
      if (i + len > n)
        return i;
      if (p[i + 1] < lo || p[i + 1] > hi)
        return i;
      for (std::size_t k = 2; k < len; ++k)
        if (p[i + k] < 0x80 || p[i + k] > 0xBF)
          return i;
      i += len;
    }
    return std::string::npos;
  }

  std::string json_text(const json &value, const int indent)
  {
    return value.dump(indent, ' ', false, json::error_handler_t::replace);
  }

  std::string json_excerpt(const json &value, const std::size_t max_chars)
  {
    std::string s;
    try
    {
      s = value.dump(-1, ' ', false, json::error_handler_t::replace);
    }
    catch (...)
    {
      s = "(value)";
    }
    if (s.size() > max_chars)
    {
      s.resize(max_chars);
      // Do not cut inside a multi-byte character.
      while (!s.empty() && (static_cast<unsigned char>(s.back()) & 0xC0) == 0x80)
        s.pop_back();
      if (!s.empty() && static_cast<unsigned char>(s.back()) >= 0xC0)
        s.pop_back();
      s += "...";
    }
    return s;
  }

  std::string read_input_file(const std::string &path, const std::size_t max_bytes)
  {
    namespace fs = std::filesystem;
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (ec || !fs::exists(status))
      throw InputError("cannot read file '" + path + "': no such file");
    if (fs::is_directory(status))
      throw InputError("cannot read file '" + path + "': it is a directory");
    std::ifstream in(path, std::ios::binary);
    if (!in)
      throw InputError("cannot read file '" + path + "': " + std::strerror(errno));
    // Read at most max_bytes + 1, so a FIFO or /dev/zero cannot make us read forever.
    std::string text;
    std::vector<char> buf(1 << 16);
    while (in && text.size() <= max_bytes)
    {
      in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
      text.append(buf.data(), static_cast<std::size_t>(in.gcount()));
    }
    if (text.size() > max_bytes)
      throw InputError(path, "", "(more than " + std::to_string(max_bytes) + " bytes)",
                       "at most " + std::to_string(max_bytes >> 20) + " MiB",
                       "too large for an input document");
    if (in.bad())
      throw InputError("cannot read file '" + path + "': read error");
    return text;
  }

  json parse_json_string(const std::string &text, const std::string &source_name)
  {
    check_utf8(text, source_name);
    JsonBuilder builder(text, source_name);
    json::sax_parse(text, &builder, json::input_format_t::json, /*strict=*/true,
                    /*ignore_comments=*/false);
    return builder.release();
  }

  json parse_yaml_string(const std::string &text, const std::string &source_name)
  {
    check_utf8(text, source_name);
    YAML::Node document;
    try
    {
      // Scan the documents first, at most two: yaml-cpp 0.7's LoadAll never ends on a stray
      // ',' at block level (",x" makes empty documents forever — found by fuzz_document); the
      // scan also stops deep nesting, naming its key path.
      std::istringstream stream(text);
      YAML::Parser parser(stream);
      DocumentScanner scanner(source_name);
      int n_documents = 0;
      while (n_documents < 2 && parser.HandleNextDocument(scanner))
        ++n_documents;
      if (n_documents > 1)
        throw InputError(source_name, "(top level)", "more than one document", "one YAML document",
                         "a '---' starts a second document, which would be ignored (or a stray "
                         "',' outside [ ] or { } ends the first one)");
      document = YAML::Load(text);
    }
    catch (const YAML::DeepRecursion &e)
    {
      throw InputError(source_name, "(top level)", "(nested mappings/lists)",
                       "at most " + std::to_string(max_document_depth) + " levels of nesting",
                       "too deep at line " + std::to_string(e.mark.line + 1));
    }
    catch (const YAML::Exception &e)
    {
      throw InputError("malformed YAML in '" + source_name + "': " + e.what());
    }
    YamlConverter converter(source_name, text.size());
    try
    {
      return converter.convert(document, "", 0);
    }
    catch (const YAML::Exception &e)
    {
      throw InputError("malformed YAML in '" + source_name + "': " + e.what());
    }
  }

  json read_json_file(const std::string &path)
  {
    return parse_json_string(read_input_file(path), path);
  }

  json read_yaml_file(const std::string &path)
  {
    return parse_yaml_string(read_input_file(path), path);
  }

  json read_structured_file(const std::string &path)
  {
    const auto ends_with = [&](const std::string &suffix) {
      return path.size() >= suffix.size() &&
             path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
    };
    if (ends_with(".json"))
      return read_json_file(path);
    return read_yaml_file(path);
  }
} // namespace clearjoint
