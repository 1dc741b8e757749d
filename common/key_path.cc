#include "common/key_path.h"

#include "common/error.h"

namespace clearjoint
{
  void set_key_path(nlohmann::json &root, const std::string &key_path, const nlohmann::json &value,
                    const std::string &source)
  {
    nlohmann::json *node = &root;
    std::size_t start = 0;
    while (true)
    {
      const std::size_t dot = key_path.find('.', start);
      const std::string key = key_path.substr(start, dot == std::string::npos ? dot : dot - start);
      const bool last = dot == std::string::npos;
      if (node->is_array())
      {
        // A numeric component indexes a list: "clearance_joints.0.normal.law_file".
        const bool numeric = !key.empty() && key.find_first_not_of("0123456789") == std::string::npos;
        if (!numeric || std::stoul(key) >= node->size())
          throw InputError(source, key_path, key,
                           "an index in [0, " + std::to_string(node->size()) + ") of the list");
        node = &(*node)[std::stoul(key)];
      }
      else if (node->is_object())
      {
        if (last)
        {
          (*node)[key] = value;
          return;
        }
        if (!node->contains(key))
          (*node)[key] = nlohmann::json::object();
        node = &(*node)[key];
      }
      else
        throw InputError(source, key_path, node->dump(), "a key path through mappings and lists",
                         "'" + key + "' cannot be set inside a scalar");
      if (last)
      {
        *node = value;
        return;
      }
      start = dot + 1;
    }
  }

  const nlohmann::json *find_key_path(const nlohmann::json &root, const std::string &key_path)
  {
    const nlohmann::json *node = &root;
    std::size_t start = 0;
    while (true)
    {
      const std::size_t dot = key_path.find('.', start);
      const std::string key = key_path.substr(start, dot == std::string::npos ? dot : dot - start);
      if (node->is_object() && node->contains(key))
        node = &(*node)[key];
      else if (node->is_array() && !key.empty() &&
               key.find_first_not_of("0123456789") == std::string::npos &&
               std::stoul(key) < node->size())
        node = &(*node)[std::stoul(key)];
      else
        return nullptr;
      if (dot == std::string::npos)
        return node;
      start = dot + 1;
    }
  }
} // namespace clearjoint
