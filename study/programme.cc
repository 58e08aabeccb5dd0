#include "study/programme.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <toml.hpp>

#include "common/config.h"
#include "common/error.h"
#include "common/key_table.h"

namespace granasym::study {

const KeyTable& ProgrammeKeys() {
  auto integer = [](std::string table, std::string name, Range range, std::string fallback,
                    std::string meaning) {
    return NumberKey(std::move(table), std::move(name), KeyType::kInteger, "", range,
                     std::move(fallback), std::move(meaning));
  };
  static const KeyTable table(
      "programme",
      "a study programme (granasym study run PROGRAMME): the sample, the scales, the shared "
      "scene tables and the runs that expand into cases (layout: study/programme.h). Scene "
      "tables: granasym keys scene; [[run.stage]] tables: granasym keys stage; [figures]: "
      "granasym keys figures",
      {
          OtherKey("", "study", KeyType::kTable, "", "required", "the programme's name and NCL"),
          OtherKey("", "scale", KeyType::kTable, "tiny, small, medium, paper", "required",
                   "one table per scale: sphere count, replicates, restrictions"),
          OtherKey("", "sample", KeyType::kTable, "", "the defaults below",
                   "the generated sample at its reference count and cell"),
          OtherKey("", "scene", KeyType::kTable, "material, numerics, output (granasym keys scene)",
                   "none", "scene tables shared by every run"),
          OtherKey("", "run", KeyType::kTables, "", "required",
                   "DEM runs; lists in vary expand into cases"),
          OtherKey("", "model_run", KeyType::kTables, "", "none",
                   "constitutive-model element tests (the tables of granasym model run)"),
          OtherKey("", "figures", KeyType::kTable, "granasym keys figures", "none",
                   "what granasym study figures draws"),
          OtherKey("study", "name", KeyType::kString, "a name", "required", "the programme's name"),
          OtherKey("study", "description", KeyType::kString, "text", "none", "one line about it"),
          OtherKey("study", "ncl", KeyType::kString, "a case name", "none",
                   "the run whose psi_epsilon = 0 stages give the study's NCL (OCR, p_e*)"),
          integer("scale.*", "count", Range::Closed(2, 2000000000), "required",
                  "spheres of the sample (the cell follows at constant porosity)"),
          integer("scale.*", "replicates", Range::Closed(1, 1000), "1",
                  "samples with seeds seed, seed + 1, ..."),
          OtherKey("scale.*", "only", KeyType::kTable, "variable = [values]", "every value",
                   "the values of vary/each lists kept at this scale"),
          OtherKey("scale.*", "variables", KeyType::kTable, "name = value", "none",
                   "placeholders {name} with a value at this scale (every scale the same names)"),
          integer("sample", "reference_count", Range::Closed(2, 2000000000), "150000",
                  "the count at which the cell is reference_cell_size_mm"),
          {"sample", "reference_cell_size_mm", KeyType::kNumber, "mm", Range::Closed(1e-3, 1e6), "",
           "31", "the cell side at reference_count", ""},
          integer("sample", "seed", Range::Closed(0, 9007199254740992.0), "1",
                  "seed of the first replicate's sample"),
          integer("sample", "max_attempts", Range::Closed(1, 1000000000), "200000",
                  "random positions tried per sphere"),
          OtherKey("sample", "gsd", KeyType::kString, "a CSV file (relative to the programme)",
                   "the reduced Zbraslav GSD", "the grain-size distribution"),
          OtherKey("run[]", "name", KeyType::kString, "a folder name; {var} placeholders",
                   "required", "the cases' names"),
          OtherKey("run[]", "from", KeyType::kString, "sample, RUN or RUN@STAGE", "required",
                   "the state the cases start from"),
          OtherKey("run[]", "vary", KeyType::kTable, "variable = [values]", "none",
                   "every combination of the lists is one case"),
          OtherKey("run[]", "figures", KeyType::kString,
                   "comma-separated figure numbers 1-22, Sec. N, rate", "none",
                   "what the cases serve"),
          OtherKey("run[]", "scene", KeyType::kTable, "material, numerics, output", "none",
                   "overrides of the shared scene tables"),
          OtherKey("run[]", "stage", KeyType::kTables, "stage tables (granasym keys stage) + each",
                   "required", "the run's stages"),
          OtherKey("run[].stage[]", "each", KeyType::kTable, "variable = [values]", "none",
                   "repeat this stage for every value"),
          OtherKey("model_run[]", "name", KeyType::kString, "a name; {var} placeholders",
                   "required", "the element tests' names"),
          OtherKey("model_run[]", "vary", KeyType::kTable, "variable = [values]", "none",
                   "every combination is one test"),
          OtherKey("model_run[]", "figures", KeyType::kString, "as run.figures", "none",
                   "what the tests serve"),
          OtherKey("model_run[]", "model", KeyType::kTable, "granasym model run's [model]",
                   "required", "the model and its parameters"),
          OtherKey("model_run[]", "initial", KeyType::kTable, "granasym model run's [initial]",
                   "required", "the initial state"),
          OtherKey("model_run[]", "integration", KeyType::kTable,
                   "granasym model run's [integration]", "the model's defaults", "the integrator"),
          OtherKey("model_run[]", "stage", KeyType::kTables, "granasym model run's [[stage]]",
                   "required", "the loading"),
      });
  return table;
}
namespace {

// Sorted tables, so that a generated scene is the same text every time.
using Value = toml::basic_value<toml::discard_comments, std::map, std::vector>;
using Table = Value::table_type;
using Array = Value::array_type;
using Variables = std::map<std::string, Value>;

[[noreturn]] void Fail(const std::string& origin, const std::string& key,
                       const std::string& message) {
  throw InputError(origin + ": " + (key.empty() ? "" : "key '" + key + "' ") + message);
}

std::string TypeName(const Value& value) {
  std::ostringstream out;
  out << value.type();
  return out.str();
}

// Rejects keys of `table` outside those of its table in ProgrammeKeys()
// (`pattern`: "", "study", "scale.*", "run[]", ...), naming the valid ones.
void CheckKeys(const std::string& origin, const std::string& prefix, const Table& table,
               const std::string& pattern) {
  std::set<std::string> allowed;
  for (const KeySpec& spec : ProgrammeKeys().keys()) {
    if (spec.table != pattern) continue;
    allowed.insert(spec.key);
    ProgrammeKeys().MarkConsulted(&spec);
  }
  GRANASYM_CHECK(!allowed.empty()) << "the programme key table has no table '" << pattern << "'";
  for (const auto& [key, value] : table) {
    if (allowed.count(key)) continue;
    std::string valid;
    for (const std::string& name : allowed) valid += (valid.empty() ? "" : ", ") + name;
    Fail(origin, prefix + key, "is not known here: valid keys are " + valid);
  }
}

// Marks a key that the parser reads outside CheckKeys as read from the table.
void ConsultKey(const std::string& pattern, const std::string& key) {
  bool found = false;
  for (const KeySpec& spec : ProgrammeKeys().keys()) {
    if (spec.table == pattern && spec.key == key) {
      ProgrammeKeys().MarkConsulted(&spec);
      found = true;
    }
  }
  GRANASYM_CHECK(found) << "the programme key table lacks " << pattern << "." << key;
}

// `key` may be a dotted name for messages ("study.name"): the table is
// searched for its last part.
const Value* FindKey(const Table& table, const std::string& key) {
  const size_t dot = key.rfind('.');
  const auto it = table.find(dot == std::string::npos ? key : key.substr(dot + 1));
  return it == table.end() ? nullptr : &it->second;
}

const Table& TableAt(const std::string& origin, const std::string& key, const Value& value) {
  if (!value.is_table()) Fail(origin, key, "must be a table, not a " + TypeName(value));
  return value.as_table();
}

std::string StringAt(const std::string& origin, const std::string& key, const Table& table,
                     const std::string& fallback, bool required) {
  const Value* value = FindKey(table, key);
  if (!value) {
    if (required) Fail(origin, key, "is missing");
    return fallback;
  }
  if (!value->is_string()) Fail(origin, key, "must be a string, not a " + TypeName(*value));
  return value->as_string().str;
}

int64_t IntAt(const std::string& origin, const std::string& key, const Table& table,
              int64_t fallback, int64_t min, int64_t max) {
  const Value* value = FindKey(table, key);
  if (!value) return fallback;
  if (!value->is_integer()) Fail(origin, key, "must be an integer, not a " + TypeName(*value));
  const int64_t v = value->as_integer();
  if (v < min || v > max) {
    Fail(origin, key,
         "= " + std::to_string(v) + " is out of range: expected an integer in [" +
             std::to_string(min) + ", " + std::to_string(max) + "]");
  }
  return v;
}

double DoubleAt(const std::string& origin, const std::string& key, const Table& table,
                double fallback) {
  const Value* value = FindKey(table, key);
  if (!value) return fallback;
  double v = 0;
  if (value->is_floating()) {
    v = value->as_floating();
  } else if (value->is_integer()) {
    v = static_cast<double>(value->as_integer());
  } else {
    Fail(origin, key, "must be a number, not a " + TypeName(*value));
  }
  // The only number read here is a cell side in mm: the scene's range.
  if (!std::isfinite(v) || v < 1e-3 || v > 1e6) {
    Fail(origin, key, fmt::format("= {:g} is out of range: must be in [0.001, 1e+06] (mm)", v));
  }
  return v;
}

// The shortest decimal text that reads back as exactly `value` (an integral
// value as an integer: 90.0 is "90", not "9e+01").
std::string ShortestText(double value) {
  if (value == std::floor(value) && std::abs(value) < 1e15) {
    return std::to_string(static_cast<int64_t>(value));
  }
  char buffer[40];
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof buffer, "%.*g", precision, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
}

std::string ValueText(const Value& value) {
  if (value.is_string()) return value.as_string().str;
  if (value.is_integer()) return std::to_string(value.as_integer());
  if (value.is_floating()) return ShortestText(value.as_floating());
  if (value.is_boolean()) return value.as_boolean() ? "true" : "false";
  return toml::format(value);
}

// Replaces the placeholders {var} in the strings of `value` (recursively).
Value Substitute(const Value& value, const Variables& variables, const std::string& origin,
                 const std::string& where) {
  if (value.is_table()) {
    Table table;
    for (const auto& [key, item] : value.as_table()) {
      table[key] = Substitute(item, variables, origin, where + "." + key);
    }
    return Value(table);
  }
  if (value.is_array()) {
    Array array;
    for (const Value& item : value.as_array()) {
      array.push_back(Substitute(item, variables, origin, where));
    }
    return Value(array);
  }
  if (!value.is_string()) return value;
  const std::string& text = value.as_string().str;
  if (text.size() > 2 && text.front() == '{' && text.back() == '}') {
    const auto it = variables.find(text.substr(1, text.size() - 2));
    if (it != variables.end()) return it->second;
  }
  std::string out;
  for (size_t k = 0; k < text.size();) {
    if (text[k] != '{') {
      out += text[k++];
      continue;
    }
    const size_t close = text.find('}', k);
    if (close == std::string::npos) Fail(origin, where, "= '" + text + "' has an unclosed '{'");
    const std::string name = text.substr(k + 1, close - k - 1);
    const auto it = variables.find(name);
    if (it == variables.end()) {
      std::string known;
      for (const auto& [var, unused] : variables) known += (known.empty() ? "" : ", ") + var;
      Fail(origin, where,
           "= '" + text + "' uses {" + name + "}, which is not a variable here (" +
               (known.empty() ? "none is defined" : "defined: " + known) + ")");
    }
    out += ValueText(it->second);
    k = close + 1;
  }
  return Value(out);
}

// A value's identity for `only`: its kind and its shortest text, so that 100
// and 100.0 are one value and "100" (a string) another.
std::string ValueKey(const Value& value) {
  if (value.is_integer() || value.is_floating()) {
    const double number =
        value.is_integer() ? static_cast<double>(value.as_integer()) : value.as_floating();
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.17g", number);
    return std::string("n:") + buffer;
  }
  return "s:" + ValueText(value);
}

// The scale's lists and placeholders while a programme is expanded.
struct ScaleExpansion {
  Scale scale = Scale::kTiny;
  std::map<std::string, std::vector<Value>> only;  // variable → values kept
  Variables variables;                             // [scale.X.variables]

  // `list` of variable `name` with only the values this scale keeps.
  std::vector<Value> Restrict(const std::string& name, const Array& list) const {
    const auto it = only.find(name);
    if (it == only.end()) return std::vector<Value>(list.begin(), list.end());
    std::set<std::string> kept;
    for (const Value& value : it->second) kept.insert(ValueKey(value));
    std::vector<Value> out;
    for (const Value& item : list) {
      if (kept.count(ValueKey(item))) out.push_back(item);
    }
    return out;
  }
};

// The values of every `vary` and `each` list of the programme, by variable
// (as ValueKey), read before the expansion so that a restriction that could
// take no effect (a misspelt variable or value) is named as such.
std::map<std::string, std::set<std::string>> ListValues(const Table& top) {
  std::map<std::string, std::set<std::string>> values;
  auto add = [&values](const Value* lists) {
    if (!lists || !lists->is_table()) return;
    for (const auto& [name, list] : lists->as_table()) {
      if (!list.is_array()) continue;
      for (const Value& item : list.as_array()) values[name].insert(ValueKey(item));
    }
  };
  for (const char* entries : {"run", "model_run"}) {
    const Value* array = FindKey(top, entries);
    if (!array || !array->is_array()) continue;
    for (const Value& entry : array->as_array()) {
      if (!entry.is_table()) continue;
      add(FindKey(entry.as_table(), "vary"));
      const Value* stages = FindKey(entry.as_table(), "stage");
      if (!stages || !stages->is_array()) continue;
      for (const Value& stage : stages->as_array()) {
        if (stage.is_table()) add(FindKey(stage.as_table(), "each"));
      }
    }
  }
  return values;
}

// Every combination of the lists of `vary` (the last key varies fastest),
// restricted to the values the scale keeps; none when a list is left empty.
std::vector<Variables> Combinations(const std::string& origin, const std::string& key,
                                    const Value* vary, const ScaleExpansion& expansion) {
  std::vector<Variables> combinations{Variables{}};
  if (!vary) return combinations;
  // The product of the lists' lengths, refused above kMaxCases before any
  // combination is made (a 10^6-case `vary` would otherwise be expanded,
  // planned and scheduled for minutes).
  double product = 1;
  std::string factors;
  for (const auto& [name, list] : TableAt(origin, key, *vary)) {
    if (!list.is_array()) continue;
    const size_t kept = expansion.Restrict(name, list.as_array()).size();
    product *= static_cast<double>(kept);
    factors += (factors.empty() ? "" : " × ") + name + " (" + std::to_string(kept) + ")";
  }
  if (product > static_cast<double>(Programme::kMaxCases)) {
    Fail(origin, key,
         fmt::format("gives {:.0f} combinations ({}): a programme may have at most {} cases; "
                     "split it or shorten the lists",
                     product, factors, Programme::kMaxCases));
  }
  for (const auto& [name, list] : TableAt(origin, key, *vary)) {
    if (!list.is_array() || list.as_array().empty()) {
      Fail(origin, key + "." + name, "must be a non-empty array of values");
    }
    if (expansion.variables.count(name)) {
      Fail(origin, key + "." + name,
           "is also a variable of [scale." + std::string(ToString(expansion.scale)) +
               ".variables]: give each placeholder one source");
    }
    for (const Value& item : list.as_array()) {
      if (item.is_table() || item.is_array()) {
        Fail(origin, key + "." + name, "must hold numbers or strings, not " + TypeName(item));
      }
    }
    std::vector<Variables> next;
    for (const Variables& partial : combinations) {
      for (const Value& item : expansion.Restrict(name, list.as_array())) {
        Variables extended = partial;
        extended[name] = item;
        next.push_back(std::move(extended));
      }
    }
    combinations = std::move(next);
  }
  return combinations;
}

bool ValidName(const std::string& name) {
  if (name.empty() || name == "." || name == ".." || name == "sample") return false;
  for (char c : name) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) {
      return false;
    }
  }
  return true;
}

// Merges `over` into `base` table by table (a value of `over` replaces).
void MergeInto(Table& base, const Table& over) {
  for (const auto& [key, value] : over) {
    auto it = base.find(key);
    if (it != base.end() && it->second.is_table() && value.is_table()) {
      MergeInto(it->second.as_table(), value.as_table());
    } else {
      base[key] = value;
    }
  }
}

std::string FormatTable(const Table& table) {
  std::ostringstream out;
  out << toml::format(Value(table), 0);
  return out.str();
}

// The sections of a programme, in the order Programme::Parse reads them.

const Table kEmpty;

// The table `key` of `top`, or an empty one when it is absent.
const Table& OptionalTable(const std::string& origin, const Table& top, const std::string& key) {
  const Value* value = FindKey(top, key);
  return value ? TableAt(origin, key, *value) : kEmpty;
}

// [study]: the name, description and NCL case.
void ParseStudy(const std::string& origin, const Table& top, Programme* programme) {
  const Table& study = OptionalTable(origin, top, "study");
  CheckKeys(origin, "study.", study, "study");
  programme->name = StringAt(origin, "study.name", study, "", true);
  programme->description = StringAt(origin, "study.description", study, "", false);
  programme->ncl_case = StringAt(origin, "study.ncl", study, "", false);
}

// One [scale.<name>] table: its count and replicates, its `only` lists
// (into `only` as values) and its `variables` (into `variables`).
ScaleSpec ParseScale(const std::string& origin, const std::string& name, const Value& value,
                     std::map<std::string, std::vector<Value>>* only, Variables* variables) {
  const std::string prefix = "scale." + name + ".";
  const Table& table = TableAt(origin, "scale." + name, value);
  CheckKeys(origin, prefix, table, "scale.*");
  ScaleSpec spec;
  if (!FindKey(table, "count")) Fail(origin, prefix + "count", "is missing");
  spec.count = IntAt(origin, prefix + "count", table, 0, 2, 2000000000);
  spec.replicates = static_cast<int>(IntAt(origin, prefix + "replicates", table, 1, 1, 1000));
  if (const Value* restrictions = FindKey(table, "only")) {
    for (const auto& [variable, list] : TableAt(origin, prefix + "only", *restrictions)) {
      const std::string where = prefix + "only." + variable;
      if (!list.is_array() || list.as_array().empty()) {
        Fail(origin, where, "must be a non-empty array of the values kept");
      }
      for (const Value& item : list.as_array()) {
        if (!(item.is_string() || item.is_integer() || item.is_floating())) {
          Fail(origin, where, "must hold numbers or strings, not " + TypeName(item));
        }
        (*only)[variable].push_back(item);
        spec.only[variable].push_back(ValueText(item));
      }
    }
  }
  if (const Value* defined = FindKey(table, "variables")) {
    for (const auto& [variable, item] : TableAt(origin, prefix + "variables", *defined)) {
      if (item.is_table() || item.is_array()) {
        Fail(origin, prefix + "variables." + variable,
             "must be a number, a string or a boolean, not " + TypeName(item));
      }
      (*variables)[variable] = item;
      spec.variables[variable] = ValueText(item);
    }
  }
  return spec;
}

// [scale.*]: every scale into the programme, each defining the same
// placeholders; returns the lists and placeholders of `scale`, whose
// restrictions are checked against the programme's lists.
ScaleExpansion ParseScales(const std::string& origin, const Table& top, Scale scale,
                           Programme* programme) {
  const Value* scales = FindKey(top, "scale");
  if (!scales) Fail(origin, "scale", "is missing: give [scale.tiny], [scale.small], [scale.paper]");
  ScaleExpansion expansion;
  expansion.scale = scale;
  std::optional<std::set<std::string>> variable_names;  // the same at every scale
  std::string first_scale;
  for (const auto& [name, value] : TableAt(origin, "scale", *scales)) {
    const std::optional<Scale> parsed = FromString<Scale>(name);
    if (!parsed) {
      Fail(origin, "scale." + name, "is not a scale: expected " + AllowedNames<Scale>());
    }
    std::map<std::string, std::vector<Value>> only;
    Variables variables;
    const ScaleSpec spec = ParseScale(origin, name, value, &only, &variables);
    std::set<std::string> names;
    for (const auto& [variable, unused] : variables) names.insert(variable);
    if (!variable_names) {
      variable_names = names;
      first_scale = name;
    } else if (*variable_names != names) {
      auto list = [](const std::set<std::string>& set) {
        std::string text;
        for (const std::string& n : set) text += (text.empty() ? "" : ", ") + n;
        return text.empty() ? std::string("none") : text;
      };
      Fail(origin, "scale." + name + ".variables",
           "defines " + list(names) + " but [scale." + first_scale + ".variables] defines " +
               list(*variable_names) + ": every scale gives the same placeholders");
    }
    if (*parsed == scale) {
      expansion.only = std::move(only);
      expansion.variables = std::move(variables);
    }
    programme->scales[*parsed] = spec;
  }
  programme->At(scale);  // the scale asked for exists
  return expansion;
}

// `[scale.X.only]` against the programme's `vary` and `each` lists: a
// restriction that could take no effect is an error.
void CheckRestrictions(const std::string& origin, const Table& top,
                       const ScaleExpansion& expansion) {
  const std::map<std::string, std::set<std::string>> list_values = ListValues(top);
  for (const auto& [variable, values] : expansion.only) {
    const std::string where =
        "scale." + std::string(ToString(expansion.scale)) + ".only." + variable;
    const auto it = list_values.find(variable);
    if (it == list_values.end()) {
      Fail(origin, where, "names no variable of a `vary` or `each` list of the programme");
    }
    for (const Value& value : values) {
      if (!it->second.count(ValueKey(value))) {
        Fail(origin, where,
             "keeps " + ValueText(value) + ", which no list of '" + variable + "' holds");
      }
    }
  }
}

// [sample]; a relative GSD path is resolved against `base_directory`.
void ParseSample(const std::string& origin, const Table& top, const std::string& base_directory,
                 SampleSpec* s) {
  const Table& sample = OptionalTable(origin, top, "sample");
  CheckKeys(origin, "sample.", sample, "sample");
  s->reference_count =
      IntAt(origin, "sample.reference_count", sample, s->reference_count, 2, 2000000000);
  s->reference_cell_size_mm =
      DoubleAt(origin, "sample.reference_cell_size_mm", sample, s->reference_cell_size_mm);
  s->seed = IntAt(origin, "sample.seed", sample, s->seed, 0, int64_t{1} << 53);
  s->max_attempts = IntAt(origin, "sample.max_attempts", sample, s->max_attempts, 1, 1000000000);
  const std::string gsd = StringAt(origin, "sample.gsd", sample, "", false);
  if (!gsd.empty()) {
    s->gsd_path = std::filesystem::path(gsd).is_absolute()
                      ? gsd
                      : (std::filesystem::path(base_directory) / gsd).lexically_normal().string();
  }
}

// [scene]: the tables every run's scene starts from.
Table SharedScene(const std::string& origin, const Table& top) {
  Table shared;
  if (const Value* scene = FindKey(top, "scene")) {
    shared = TableAt(origin, "scene", *scene);
    for (const auto& [key, unused] : shared) {
      if (key == "sample" || key == "stage") {
        Fail(origin, "scene." + key,
             "cannot be shared: the sample comes from [sample] or `from`, stages from "
             "[[run.stage]]");
      }
    }
  }
  return shared;
}

// A case's `from` ("sample", "RUN" or "RUN@STAGE") against the cases before it.
// `names`: the index in programme.cases of each case so far.
void ResolveParent(const std::string& origin, const std::string& case_where,
                   const std::string& from, const Programme& programme,
                   const std::map<std::string, size_t>& names, CaseSpec* spec) {
  if (from == "sample") return;
  const size_t at = from.find('@');
  spec->parent = from.substr(0, at);
  if (at != std::string::npos) {
    spec->parent_stage = from.substr(at + 1);
    // "RUN@" would fork from the final state as if no stage were named.
    if (spec->parent_stage.empty()) {
      Fail(origin, case_where + ".from",
           "= '" + from + "' names no stage after '@': give \"" + spec->parent + "@STAGE\" or \"" +
               spec->parent + "\" (its final state)");
    }
  }
  const auto found_parent = names.find(spec->parent);
  const CaseSpec* parent =
      found_parent == names.end() ? nullptr : &programme.cases[found_parent->second];
  const Scale scale = programme.scale;
  if (!parent) {
    Fail(origin, case_where + ".from",
         "= '" + from + "' names no earlier case at scale " + ToString(scale) +
             ": parents come before their children (and [scale." + ToString(scale) +
             ".only] keeps a child only with its parent)");
  }
  if (spec->parent_stage.empty()) return;
  bool found = false;
  for (const std::string& stage : parent->stage_names) found |= stage == spec->parent_stage;
  if (!found) {
    std::string known;
    for (const std::string& stage : parent->stage_names) {
      known += (known.empty() ? "" : ", ") + stage;
    }
    Fail(origin, case_where + ".from",
         "= '" + from + "': case '" + spec->parent + "' has no stage '" + spec->parent_stage +
             "' (its stages: " + known + ")");
  }
}

// The [[run.stage]] tables of a case, each repeated for its `each` lists;
// their names go into the case.
Array ExpandStages(const std::string& origin, const std::string& where, const Array& stages,
                   const Variables& variables, const ScaleExpansion& expansion, CaseSpec* spec) {
  Array stage_tables;
  for (size_t k = 0; k < stages.size(); ++k) {
    const std::string stage_where = where + ".stage[" + std::to_string(k + 1) + "]";
    Table stage = TableAt(origin, stage_where, stages[k]);
    ConsultKey("run[].stage[]", "each");
    const bool repeats = stage.count("each") > 0;
    const Value each = repeats ? stage.at("each") : Value();
    stage.erase("each");
    for (const Variables& repeat :
         Combinations(origin, stage_where + ".each", repeats ? &each : nullptr, expansion)) {
      Variables all = variables;
      for (const auto& [var, value] : repeat) all[var] = value;
      Value expanded = Substitute(Value(stage), all, origin, stage_where);
      const Table& table = expanded.as_table();
      const std::string stage_name =
          StringAt(origin, stage_where + ".name", table,
                   "stage" + std::to_string(stage_tables.size() + 1), false);
      for (const std::string& existing : spec->stage_names) {
        if (existing == stage_name) {
          Fail(origin, stage_where + ".name",
               "gives '" + stage_name + "' twice in case '" + spec->name + "'");
        }
      }
      spec->stage_names.push_back(stage_name);
      // A strain-path stage's ψ_ε (the default type), for the NCL check.
      const auto type = table.find("type");
      const auto psi = table.find("psi_epsilon_deg");
      const bool strain_path = type == table.end() || (type->second.is_string() &&
                                                       type->second.as_string() == "strain_path");
      spec->stage_psi_epsilon.push_back(
          strain_path && psi != table.end() &&
                  (psi->second.is_floating() || psi->second.is_integer())
              ? (psi->second.is_floating() ? psi->second.as_floating()
                                           : static_cast<double>(psi->second.as_integer()))
              : std::numeric_limits<double>::quiet_NaN());
      stage_tables.push_back(expanded);
    }
  }
  if (stage_tables.empty()) {
    const Scale scale = expansion.scale;
    Fail(origin, where + ".stage",
         "gives case '" + spec->name + "' no stage at scale " + ToString(scale) + ": [scale." +
             ToString(scale) + ".only] leaves its `each` lists empty");
  }
  return stage_tables;
}

// One [[run]] (`where`: "run[K]") into its cases, one per combination of its
// `vary` lists; `names` holds the case names so far.
void ExpandRun(const std::string& origin, const std::string& where, const Table& run,
               const Table& shared, const ScaleExpansion& expansion,
               std::map<std::string, size_t>* names, Programme* programme) {
  CheckKeys(origin, where + ".", run, "run[]");
  const std::string name_template = StringAt(origin, where + ".name", run, "", true);
  const std::string from_template = StringAt(origin, where + ".from", run, "", true);
  const FigureSet figures = FigureSet::Parse(StringAt(origin, where + ".figures", run, "", false),
                                             origin, where + ".figures");
  const Value* stages = FindKey(run, "stage");
  if (!stages || !stages->is_array() || stages->as_array().empty()) {
    Fail(origin, where + ".stage", "is missing: a run needs at least one [[run.stage]]");
  }
  Table overrides;
  if (const Value* scene = FindKey(run, "scene")) {
    overrides = TableAt(origin, where + ".scene", *scene);
  }
  for (Variables variables :
       Combinations(origin, where + ".vary", FindKey(run, "vary"), expansion)) {
    CaseSpec spec;
    spec.run = name_template;
    spec.figures = figures;
    for (const auto& [var, value] : variables) spec.variables[var] = ValueText(value);
    for (const auto& [var, value] : expansion.variables) variables[var] = value;
    spec.name =
        Substitute(Value(name_template), variables, origin, where + ".name").as_string().str;
    if (!ValidName(spec.name)) {
      Fail(origin, where + ".name",
           "gives '" + spec.name +
               "', which is not a valid case name (letters, digits, '_', '-', '.'; not "
               "'sample')");
    }
    if (spec.name.size() > Programme::kMaxNameLength) {
      Fail(origin, where + ".name",
           fmt::format("gives '{}…' of {} characters: a case name (a folder name) has at most {}",
                       spec.name.substr(0, 40), spec.name.size(), Programme::kMaxNameLength));
    }
    if (names->count(spec.name)) {
      Fail(origin, where + ".name", "gives '" + spec.name + "' twice: case names are unique");
    }
    const std::string from =
        Substitute(Value(from_template), variables, origin, where + ".from").as_string().str;
    ResolveParent(origin, where + " (case '" + spec.name + "')", from, *programme, *names, &spec);
    Table scene = shared;
    MergeInto(scene, Substitute(Value(overrides), variables, origin, where + ".scene").as_table());
    scene["stage"] =
        Value(ExpandStages(origin, where, stages->as_array(), variables, expansion, &spec));
    spec.scene_body = FormatTable(scene);
    names->emplace(spec.name, programme->cases.size());
    programme->cases.push_back(std::move(spec));
  }
}

// [[run]]: every case of the programme, parents before their children.
void ExpandRuns(const std::string& origin, const Table& top, const ScaleExpansion& expansion,
                Programme* programme) {
  const Table shared = SharedScene(origin, top);
  const Value* runs = FindKey(top, "run");
  if (!runs || !runs->is_array() || runs->as_array().empty()) {
    Fail(origin, "run", "is missing: a programme needs at least one [[run]]");
  }
  std::map<std::string, size_t> names;  // case name → index in programme->cases
  for (size_t r = 0; r < runs->as_array().size(); ++r) {
    const std::string where = "run[" + std::to_string(r + 1) + "]";
    const Table& run = TableAt(origin, where, runs->as_array()[r]);
    ExpandRun(origin, where, run, shared, expansion, &names, programme);
  }
}

// [[model_run]]: the element tests of the constitutive models.
void ExpandModelRuns(const std::string& origin, const Table& top, const ScaleExpansion& expansion,
                     Programme* programme) {
  const Value* models = FindKey(top, "model_run");
  if (!models) return;
  if (!models->is_array()) Fail(origin, "model_run", "must be an array of tables [[model_run]]");
  std::set<std::string> model_names;
  for (size_t m = 0; m < models->as_array().size(); ++m) {
    const std::string where = "model_run[" + std::to_string(m + 1) + "]";
    const Table& entry = TableAt(origin, where, models->as_array()[m]);
    CheckKeys(origin, where + ".", entry, "model_run[]");
    const std::string name_template = StringAt(origin, where + ".name", entry, "", true);
    for (Variables variables :
         Combinations(origin, where + ".vary", FindKey(entry, "vary"), expansion)) {
      ModelCaseSpec spec;
      spec.name =
          Substitute(Value(name_template), variables, origin, where + ".name").as_string().str;
      if (!ValidName(spec.name) || !model_names.insert(spec.name).second) {
        Fail(origin, where + ".name",
             "gives '" + spec.name + "': model runs need unique, valid folder names");
      }
      spec.figures = FigureSet::Parse(StringAt(origin, where + ".figures", entry, "", false),
                                      origin, where + ".figures");
      for (const auto& [var, value] : variables) spec.variables[var] = ValueText(value);
      for (const auto& [var, value] : expansion.variables) variables[var] = value;
      Table test;
      for (const char* key : {"model", "initial", "integration", "stage"}) {
        if (const Value* value = FindKey(entry, key)) {
          test[key] = Substitute(*value, variables, origin, where + "." + key);
        }
      }
      spec.text = FormatTable(test);
      programme->model_cases.push_back(std::move(spec));
    }
  }
}

}  // namespace

double SampleSpec::CellSizeMm(int64_t count) const {
  return reference_cell_size_mm *
         std::cbrt(static_cast<double>(count) / static_cast<double>(reference_count));
}

Programme Programme::Load(const std::string& path, Scale scale) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the programme file");
  std::stringstream text;
  text << in.rdbuf();
  return Parse(text.str(), path, std::filesystem::path(path).parent_path().string(), scale);
}

Programme Programme::Parse(const std::string& text, const std::string& origin,
                           const std::string& base_directory, Scale scale) {
  Value root;
  try {
    std::istringstream in(text);
    root = toml::parse<toml::discard_comments, std::map, std::vector>(in, origin);
  } catch (const toml::syntax_error& error) {
    throw InputError(origin + ": TOML syntax error: " + error.what());
  }
  const Table& top = root.as_table();
  CheckKeys(origin, "", top, "");
  Programme programme;
  programme.origin = origin;
  programme.scale = scale;
  ParseStudy(origin, top, &programme);
  if (FindKey(top, "figures")) {
    const ConfigTable file = ConfigTable::ParseString(text, origin);
    programme.figures = FigureSettings::FromConfig(file.GetTable("figures"));
  }
  const ScaleExpansion expansion = ParseScales(origin, top, scale, &programme);
  CheckRestrictions(origin, top, expansion);
  ParseSample(origin, top, base_directory, &programme.sample);
  ExpandRuns(origin, top, expansion, &programme);
  ExpandModelRuns(origin, top, expansion, &programme);
  const double total = static_cast<double>(programme.cases.size()) *
                       static_cast<double>(programme.Current().replicates);
  if (total > static_cast<double>(Programme::kMaxCases)) {
    Fail(origin, "run",
         fmt::format("gives {} cases × {} replicates = {:.0f} at scale {}: a programme may have "
                     "at most {} cases; split it or shorten the lists",
                     programme.cases.size(), programme.Current().replicates, total, ToString(scale),
                     Programme::kMaxCases));
  }
  if (programme.cases.empty()) {
    Fail(origin, "scale." + std::string(ToString(scale)) + ".only",
         "leaves the programme no case at this scale");
  }
  if (!programme.ncl_case.empty() && !programme.Find(programme.ncl_case)) {
    Fail(origin, "study.ncl",
         "= '" + programme.ncl_case + "' names no case of the programme at scale " +
             ToString(scale));
  }
  if (const CaseSpec* ncl =
          programme.ncl_case.empty() ? nullptr : programme.Find(programme.ncl_case)) {
    const bool isotropic = std::any_of(ncl->stage_psi_epsilon.begin(), ncl->stage_psi_epsilon.end(),
                                       [](double psi) { return std::abs(psi) < 1e-9; });
    if (!isotropic) {
      Fail(origin, "study.ncl",
           "= '" + programme.ncl_case +
               "' has no isotropic compression stage (a strain_path stage with "
               "psi_epsilon_deg = 0): the NCL, against which OCR and p_e* are measured, comes "
               "from such stages");
    }
  }
  return programme;
}

const CaseSpec* Programme::Find(const std::string& name) const {
  for (const CaseSpec& spec : cases) {
    if (spec.name == name) return &spec;
  }
  return nullptr;
}

const ScaleSpec& Programme::At(Scale scale) const {
  const auto it = scales.find(scale);
  if (it == scales.end()) {
    std::string known;
    for (const auto& [s, unused] : scales)
      known += std::string(known.empty() ? "" : ", ") + ToString(s);
    throw InputError(origin + ": the programme has no [scale." + ToString(scale) + "] (it has " +
                     known + ")");
  }
  return it->second;
}

}  // namespace granasym::study
