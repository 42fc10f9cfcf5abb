#include "app/option_arity.h"

#include <cerrno>
#include <cstdlib>
#include <map>
#include <sstream>

#include "core/error.h"

namespace glint {

namespace {

struct Arity {
  int count = 0;
  ValueKind kind = ValueKind::Number;
  std::string names;
};

// Keyed by the subcommand's and the option's names (CLI11 keeps no place for it): an option's
// address may be another option's once its app is gone.
std::map<std::pair<std::string, std::string>, Arity>& arities() {
  static std::map<std::pair<std::string, std::string>, Arity> table;
  return table;
}

bool isOfKind(const std::string& text, ValueKind kind) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  if (kind == ValueKind::Integer) {
    (void)std::strtoll(text.c_str(), &end, 0);  // base 0, as CLI11 converts it
    return *end == '\0' && errno != ERANGE;
  }
  (void)std::strtod(text.c_str(), &end);
  return *end == '\0';
}

// Whether an argument is an option's name rather than a value: it starts with '-' and is not a
// number ("-1", "-1e19" and "-inf" are values).
bool isOptionName(const std::string& text) {
  return text.size() > 1 && text[0] == '-' && !isOfKind(text, ValueKind::Number);
}

// An argument's values: its words, or itself when it has none (an empty argument is a value,
// and not an integer).
std::vector<std::string> words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  if (out.empty()) out.push_back(text);
  return out;
}

std::string kindName(ValueKind kind, int count) {
  const bool one = count == 1;
  return kind == ValueKind::Integer ? (one ? "integer" : "integers") : (one ? "number" : "numbers");
}

std::string joined(const std::vector<std::string>& values) {
  std::string s;
  for (const std::string& v : values)
    s += (s.empty() ? "" : " ") + (v.empty() ? std::string("\"\"") : excerpt(v));
  return s.empty() ? "none" : s;
}

}  // namespace

CLI::Option* takesValues(CLI::App& command, CLI::Option* option, int count, ValueKind kind,
                         const std::string& names) {
  arities()[{command.get_name(), option->get_name()}] = {count, kind, names};
  // No values beyond the count: CLI11 lets a vector option take every plain argument that
  // follows, the scene too.
  return option->type_size(count)->allow_extra_args(false)->type_name(names);
}

std::vector<std::string> checkArities(const CLI::App& app, std::vector<std::string> args) {
  const CLI::App* command = nullptr;
  std::vector<std::string> out;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string arg = args[i];
    if (arg == "--") {  // the rest are positionals
      out.insert(out.end(), args.begin() + long(i), args.end());
      break;
    }
    out.push_back(arg);
    if (!command) {
      for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
        if (sub->check_name(arg)) command = sub;
      continue;
    }
    if (!isOptionName(arg)) continue;
    const size_t equals = arg.find('=');
    const CLI::Option* option =
        const_cast<CLI::App*>(command)->get_option_no_throw(arg.substr(0, equals));
    const auto it =
        option ? arities().find({command->get_name(), option->get_name()}) : arities().end();
    if (it == arities().end()) continue;
    const Arity& arity = it->second;
    // The values that follow, a quoted group counting as its words.
    std::vector<std::string> values;
    if (equals != std::string::npos) {
      out.back() = arg.substr(0, equals);
      for (const std::string& w : words(arg.substr(equals + 1))) values.push_back(w);
    }
    size_t next = i + 1;
    for (; next < args.size() && args[next] != "--" && !isOptionName(args[next]); ++next) {
      const std::vector<std::string> w = words(args[next]);
      // A further plain argument after the values is the next positional (a scene), unless it
      // is one more value of the option's kind.
      if (int(values.size()) >= arity.count && !(w.size() == 1 && isOfKind(w[0], arity.kind)))
        break;
      values.insert(values.end(), w.begin(), w.end());
      if (w.size() > 1 && int(values.size()) > arity.count) break;
    }
    const std::string takes = arg.substr(0, equals) + " takes " + std::to_string(arity.count) +
                              " " + kindName(arity.kind, arity.count) + " " + arity.names;
    if (int(values.size()) != arity.count)
      throw UsageError(takes + ", got " + std::to_string(values.size()) + ": " + joined(values));
    for (const std::string& v : values)
      if (!isOfKind(v, arity.kind))
        throw UsageError(takes + ", got " + joined(values) + " (" + inQuotes(v) + " is not " +
                         (arity.kind == ValueKind::Integer ? "an integer)" : "a number)"));
    out.insert(out.end(), values.begin(), values.end());
    i = next - 1;
  }
  return out;
}

}  // namespace glint
