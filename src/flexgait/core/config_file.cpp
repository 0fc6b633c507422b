#include "flexgait/core/config_file.hpp"

#include <fmt/format.h>
#include <yaml-cpp/emitter.h>
#include <yaml-cpp/emittermanip.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/parser.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "flexgait/core/config.hpp"
#include "flexgait/core/text.hpp"

namespace flexgait {
namespace {

// The document as a tree built from the parser's events. An alias shares the node of its anchor
// (nothing is copied while parsing); flattening expands it, counting every node it visits.
struct Node;
struct Ref {
  std::shared_ptr<const Node> node;
  int line = 0;  // 1-based line where the node is used (an alias: the alias's own line)
};
struct Node {
  enum class Kind { Null, Scalar, Map, Sequence } kind = Kind::Null;
  std::string scalar;
  std::vector<std::pair<Ref, Ref>> entries;  // Map: key and value; Sequence: value only
  bool complete = false;                     // closed; an alias to an open node is recursive
};

const char* kind_name(Node::Kind k) {
  switch (k) {
    case Node::Kind::Null:
      return "null";
    case Node::Kind::Scalar:
      return "a name";
    case Node::Kind::Map:
      return "a mapping";
    case Node::Kind::Sequence:
      return "a list";
  }
  return "?";
}

class TreeBuilder : public YAML::EventHandler {
 public:
  explicit TreeBuilder(std::string name) : name_(std::move(name)) {}
  const std::optional<Ref>& root() const { return root_; }
  int document_line() const { return document_line_; }

  void OnDocumentStart(const YAML::Mark& mark) override { document_line_ = mark.line + 1; }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override { leaf(Node::Kind::Null, "", mark, anchor); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor, const std::string& value) override {
    leaf(Node::Kind::Scalar, value, mark, anchor);
  }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    const auto it = anchors_.find(anchor);
    if (it == anchors_.end()) fail(mark.line + 1, "an alias to an unknown anchor");
    if (!it->second->complete) fail(mark.line + 1, "a recursive alias (it refers to a node that contains it)");
    attach(Ref{it->second, mark.line + 1});
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    open(Node::Kind::Sequence, mark, anchor);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    open(Node::Kind::Map, mark, anchor);
  }
  void OnMapEnd() override { close(); }

 private:
  struct Open {
    std::shared_ptr<Node> node;
    std::optional<Ref> key;           // a mapping's key waiting for its value
    std::map<std::string, int> seen;  // a mapping's keys so far, with their lines
  };

  [[noreturn]] void fail(int line, const std::string& problem) const {
    throw ConfigError("", fmt::format("{}:{}: {}", name_, line, problem));
  }

  void leaf(Node::Kind kind, const std::string& value, const YAML::Mark& mark, YAML::anchor_t anchor) {
    auto node = std::make_shared<Node>();
    node->kind = kind;
    node->scalar = value;
    node->complete = true;
    if (anchor != YAML::NullAnchor) anchors_[anchor] = node;
    attach(Ref{node, mark.line + 1});
  }

  void open(Node::Kind kind, const YAML::Mark& mark, YAML::anchor_t anchor) {
    if (stack_.size() >= static_cast<std::size_t>(kMaxConfigDepth))
      fail(mark.line + 1, fmt::format("nested deeper than {} levels", kMaxConfigDepth));
    auto node = std::make_shared<Node>();
    node->kind = kind;
    if (anchor != YAML::NullAnchor) anchors_[anchor] = node;
    attach(Ref{node, mark.line + 1});
    stack_.push_back(Open{node, std::nullopt, {}});
  }

  void close() {
    stack_.back().node->complete = true;
    stack_.pop_back();
  }

  void attach(const Ref& ref) {
    if (stack_.empty()) {
      root_ = ref;
      return;
    }
    Open& top = stack_.back();
    if (top.node->kind == Node::Kind::Sequence) {
      top.node->entries.push_back({Ref{}, ref});
    } else if (top.key) {
      top.node->entries.push_back({*top.key, ref});
      top.key.reset();
    } else {
      if (ref.node->kind != Node::Kind::Scalar)
        fail(ref.line, fmt::format("a key must be a plain name, not {}", kind_name(ref.node->kind)));
      const auto [it, added] = top.seen.emplace(ref.node->scalar, ref.line);
      if (!added)
        fail(ref.line, fmt::format("key '{}' given twice (first at line {})", one_line(ref.node->scalar), it->second));
      top.key = ref;
    }
  }

  std::string name_;
  std::optional<Ref> root_;
  int document_line_ = 0;
  std::vector<Open> stack_;
  std::map<YAML::anchor_t, std::shared_ptr<Node>> anchors_;
};

struct Flattener {
  const std::string& name;
  std::size_t visited = 0;
  std::map<std::string, std::string> origins;  // dotted key -> where it was first given
  std::vector<ConfigEntry> out;

  void map(const Node& node, const std::string& prefix, int depth) {
    for (const auto& [k, v] : node.entries) {
      const std::string origin = fmt::format("{}:{}", name, v.line);
      if (++visited > kMaxConfigNodes)
        throw ConfigError("", fmt::format("{}: aliases expand to more than {} values (a configuration has a few "
                                          "hundred)",
                                          origin, kMaxConfigNodes));
      const std::string key = prefix.empty() ? k.node->scalar : prefix + "." + k.node->scalar;
      const std::string shown = one_line(key);
      switch (v.node->kind) {
        case Node::Kind::Map:
          if (depth >= kMaxConfigDepth)
            throw ConfigError(key,
                              fmt::format("{}: key '{}' nested deeper than {} levels", origin, shown, kMaxConfigDepth));
          map(*v.node, key, depth + 1);
          break;
        case Node::Kind::Scalar: {
          const auto [it, added] = origins.emplace(key, origin);
          if (!added)
            throw ConfigError(key, fmt::format("{}: key '{}' given twice (first at {})", origin, shown, it->second));
          out.push_back({key, v.node->scalar, origin});
          break;
        }
        case Node::Kind::Null:
          throw ConfigError(key, fmt::format("{}: key '{}' has no value", origin, shown));
        case Node::Kind::Sequence: {
          const auto [it, added] = origins.emplace(key, origin);
          if (!added)
            throw ConfigError(key, fmt::format("{}: key '{}' given twice (first at {})", origin, shown, it->second));
          YAML::Emitter text;
          text << YAML::Flow;
          emit(text, *v.node, origin);
          out.push_back({key, text.c_str(), origin, true});
          break;
        }
      }
    }
  }

  // A list value as flow YAML, aliases expanded (each node counted against the limit).
  void emit(YAML::Emitter& text, const Node& node, const std::string& origin) {
    if (++visited > kMaxConfigNodes)
      throw ConfigError("", fmt::format("{}: aliases expand to more than {} values (a configuration has a few "
                                        "hundred)",
                                        origin, kMaxConfigNodes));
    switch (node.kind) {
      case Node::Kind::Null:
        text << YAML::Null;
        break;
      case Node::Kind::Scalar:
        text << node.scalar;
        break;
      case Node::Kind::Sequence:
        text << YAML::BeginSeq;
        for (const auto& [k, v] : node.entries) emit(text, *v.node, origin);
        text << YAML::EndSeq;
        break;
      case Node::Kind::Map:
        text << YAML::BeginMap;
        for (const auto& [k, v] : node.entries) {
          text << YAML::Key;
          emit(text, *k.node, origin);
          text << YAML::Value;
          emit(text, *v.node, origin);
        }
        text << YAML::EndMap;
        break;
    }
  }
};

// The document's root (none when empty); syntax errors and a second document are ConfigErrors.
std::optional<Ref> parse_tree(std::string_view text, const std::string& name) {
  std::istringstream in{std::string(text)};
  TreeBuilder tree(name);
  try {
    YAML::Parser parser(in);
    if (!parser.HandleNextDocument(tree)) return std::nullopt;
    TreeBuilder second(name);
    if (parser.HandleNextDocument(second))
      throw ConfigError("", fmt::format("{}:{}: a second YAML document; a configuration is one mapping of keys", name,
                                        second.document_line()));
  } catch (const YAML::Exception& e) {
    const std::string where = e.mark.is_null() ? name : fmt::format("{}:{}", name, e.mark.line + 1);
    throw ConfigError("", fmt::format("{}: YAML syntax error: {}", where, one_line(e.msg, 200)));
  }
  return tree.root();
}

}  // namespace

std::vector<std::vector<ItemFieldText>> parse_list_text(std::string_view text) {
  const std::optional<Ref> root = parse_tree(text, "list");
  if (!root || root->node->kind != Node::Kind::Sequence) throw ConfigError("", "not a list");
  std::size_t visited = 0;
  auto count = [&] {
    if (++visited > kMaxConfigNodes) throw ConfigError("", fmt::format("more than {} values", kMaxConfigNodes));
  };
  std::vector<std::vector<ItemFieldText>> items;
  for (const auto& [unused, item] : root->node->entries) {
    count();
    if (item.node->kind != Node::Kind::Map)
      throw ConfigError(
          "", fmt::format("item {} is {}, not a mapping of fields", items.size(), kind_name(item.node->kind)));
    std::vector<ItemFieldText> fields;
    for (const auto& [k, v] : item.node->entries) {
      count();
      ItemFieldText f{k.node->scalar, {}, v.node->kind == Node::Kind::Sequence};
      if (v.node->kind == Node::Kind::Scalar) f.values.push_back(v.node->scalar);
      for (const auto& [unused2, e] : v.node->entries) {
        count();
        if (e.node->kind != Node::Kind::Scalar)
          throw ConfigError("", fmt::format("item {} field '{}' holds {}, not a value", items.size(), one_line(f.name),
                                            kind_name(e.node->kind)));
        f.values.push_back(e.node->scalar);
      }
      if (v.node->kind != Node::Kind::Scalar && v.node->kind != Node::Kind::Sequence)
        throw ConfigError("", fmt::format("item {} field '{}' is {}, not a value or a list of values", items.size(),
                                          one_line(f.name), kind_name(v.node->kind)));
      fields.push_back(std::move(f));
    }
    items.push_back(std::move(fields));
  }
  return items;
}

std::vector<ConfigEntry> parse_config_yaml(std::string_view text, const std::string& name) {
  const std::optional<Ref> root = parse_tree(text, name);
  if (!root || root->node->kind == Node::Kind::Null) return {};
  if (root->node->kind != Node::Kind::Map)
    throw ConfigError("", fmt::format("{}: the top level must be a mapping of keys", name));
  Flattener flat{name, 0, {}, {}};
  flat.map(*root->node, "", 1);
  return std::move(flat.out);
}

std::vector<ConfigEntry> read_config_file(const std::filesystem::path& file) {
  const std::string name = one_line(file.string(), 1000);
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(file, ec);
  if (st.type() == std::filesystem::file_type::not_found)
    throw ConfigError("", fmt::format("{}: cannot read configuration file: no such file", name));
  if (ec) throw ConfigError("", fmt::format("{}: cannot read configuration file: {}", name, ec.message()));
  if (std::filesystem::is_directory(st))
    throw ConfigError("", fmt::format("{}: is a directory, not a configuration file", name));
  if (!std::filesystem::is_regular_file(st))
    throw ConfigError("", fmt::format("{}: is not a regular file (a FIFO, socket or device); give a YAML file", name));
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ConfigError("", fmt::format("{}: cannot read configuration file: {}", name, std::strerror(errno)));
  std::string text(kMaxConfigBytes + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > kMaxConfigBytes)
    throw ConfigError(
        "", fmt::format("{}: larger than {} bytes; a configuration file is a few kilobytes", name, kMaxConfigBytes));
  return parse_config_yaml(text, name);
}

}  // namespace flexgait
