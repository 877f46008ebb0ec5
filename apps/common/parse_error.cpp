#include "apps/common/parse_error.h"

#include <fmt/format.h>

#include <cctype>
#include <optional>
#include <string_view>
#include <vector>

#include "core/spelling.h"

namespace glarecam::apps {
namespace {

// The app and the subcommands chosen on the command line, outermost first.
std::vector<const CLI::App*> chosenCommands(const CLI::App& app) {
  std::vector<const CLI::App*> chain{&app};
  while (!chain.back()->get_subcommands().empty())
    chain.push_back(chain.back()->get_subcommands().front());
  return chain;
}

// An option word: "-x" or "--name[=value]", not a negative number ("-5", "-0.5,2").
bool isOptionWord(std::string_view word) {
  if (word.size() < 2 || word[0] != '-') return false;
  const char next = word[1];
  return !(std::isdigit(static_cast<unsigned char>(next)) || next == '.');
}

struct KnownOption {
  std::string name;  // "--out", "-v"
  const CLI::Option* option;
};

// Every option the chosen commands accept (global options fall through to subcommands).
std::vector<KnownOption> knownOptions(const std::vector<const CLI::App*>& chain) {
  std::vector<KnownOption> known;
  for (const CLI::App* command : chain) {
    for (const CLI::Option* option : command->get_options()) {
      for (const std::string& name : option->get_lnames()) known.push_back({"--" + name, option});
      for (const std::string& name : option->get_snames()) known.push_back({"-" + name, option});
    }
  }
  return known;
}

std::string commandName(const std::vector<const CLI::App*>& chain) {
  std::string name;
  for (std::size_t i = 1; i < chain.size(); ++i)
    name += (name.empty() ? "" : " ") + chain[i]->get_name();
  return name.empty() ? std::string() : name + ": ";
}

std::string didYouMean(const std::optional<std::string>& suggestion) {
  return suggestion ? " (did you mean " + *suggestion + "?)" : std::string();
}

// Several short flags in one word ("-vq"), each known.
bool isShortFlags(std::string_view word, const std::vector<KnownOption>& known) {
  if (word.size() < 3 || word[1] == '-' || word.find('=') != std::string_view::npos) return false;
  for (const char c : word.substr(1)) {
    const std::string name{'-', c};
    if (std::none_of(known.begin(), known.end(),
                     [&](const KnownOption& k) { return k.name == name; }))
      return false;
  }
  return true;
}

// The first option word no chosen command knows, or a flag given a value.
std::optional<std::string> optionProblem(const std::vector<const CLI::App*>& chain, int argc,
                                         char** argv) {
  const std::vector<KnownOption> known = knownOptions(chain);
  std::vector<std::string> names;
  for (const KnownOption& k : known)
    if (k.name.starts_with("--")) names.push_back(k.name);
  for (int i = 1; i < argc; ++i) {
    const std::string_view word = argv[i];
    if (word == "--") break;  // positional arguments follow
    if (!isOptionWord(word)) continue;
    const std::size_t equals = word.find('=');
    const std::string name(word.substr(0, equals));
    const auto match = std::find_if(known.begin(), known.end(),
                                    [&](const KnownOption& k) { return k.name == name; });
    if (match == known.end() && isShortFlags(word, known)) continue;
    if (match == known.end()) {
      return fmt::format("{}unknown option {}{}", commandName(chain), name,
                         didYouMean(closestSpelling(name, names)));
    }
    if (equals != std::string_view::npos && match->option->get_expected_max() == 0) {
      return fmt::format("{}{} is a flag and takes no value (got \"{}\"): give {} alone",
                         commandName(chain), name, word.substr(equals + 1), name);
    }
  }
  return std::nullopt;
}

// The first word that is neither an option, an option's value nor a chosen command: what the
// user meant as a command, when the deepest chosen command wants one.
std::optional<std::string> commandProblem(const std::vector<const CLI::App*>& chain, int argc,
                                          char** argv) {
  const auto commands = chain.back()->get_subcommands({});
  if (commands.empty()) return std::nullopt;
  // A command that also takes positional arguments (`hazard SCENE` beside `hazard merge`): a
  // word that is no command is one of them, not a misspelt command.
  if (!chain.back()->get_options([](const CLI::Option* o) { return o->get_positional(); }).empty())
    return std::nullopt;
  const std::vector<KnownOption> known = knownOptions(chain);
  std::vector<std::string> names;
  for (const CLI::App* sub : commands) names.push_back(sub->get_name());
  for (int i = 1; i < argc; ++i) {
    const std::string_view word = argv[i];
    if (word == "--") break;  // positional arguments follow
    if (isOptionWord(word)) {
      const std::string_view name = word.substr(0, word.find('='));
      const auto match = std::find_if(known.begin(), known.end(),
                                      [&](const KnownOption& k) { return k.name == name; });
      // An unknown option may take the next word as its value: that option is the problem.
      if (match == known.end() && !isShortFlags(word, known)) return std::nullopt;
      if (match != known.end() && match->option->get_expected_min() > 0 && name == word) ++i;
      continue;
    }
    if (std::any_of(chain.begin() + 1, chain.end(),
                    [&](const CLI::App* c) { return c->get_name() == word; }))
      continue;
    // A known command the parse stopped before: the problem lies elsewhere.
    if (std::find(names.begin(), names.end(), word) != names.end()) return std::nullopt;
    std::string list;
    for (const std::string& name : names) list += (list.empty() ? "" : ", ") + name;
    return fmt::format("{}unknown command \"{}\"{} (known: {})", commandName(chain), word,
                       didYouMean(closestSpelling(word, names)), list);
  }
  return std::nullopt;
}

}  // namespace

std::string parseErrorMessage(const CLI::App& app, const CLI::ParseError& error, int argc,
                              char** argv) {
  const std::vector<const CLI::App*> chain = chosenCommands(app);
  if (auto problem = commandProblem(chain, argc, argv)) return *problem;
  if (auto problem = optionProblem(chain, argc, argv)) return *problem;
  return error.what();
}

}  // namespace glarecam::apps
