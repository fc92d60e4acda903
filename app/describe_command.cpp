// `mpile describe`: the case format's tables and material types in words, as the Markdown tables
// of docs/case-format.md and as a JSON Schema, all from the one declaration in
// cases/case_format.cpp.
//
// Outline:
//   a key's kind, range, choices and default in words (kind_name, allowed, material_range, ...)
//   a table or material type in words for the terminal (describe_table, describe_material)
//   Markdown tables (cell, markdown_table, markdown_material)
//   the JSON Schema's pieces (json_*, describe_key, schema_of_key, schema_of_table), table_list
//   describe_tables and case_json_schema: what `mpile describe [TABLE]` and --json-schema print
//   regenerate_doc: a doc's generated key tables written anew (--update-doc, --check-doc)
//   describe_command: the command
#include "app/describe_command.hpp"

#include "app/run_command.hpp"
#include "cases/case_error.hpp"
#include "cases/case_format.hpp"
#include "engine/materials/material_registry.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>

namespace mpile {

namespace {

std::string kind_name(const KeySpec& k) {
  switch (k.kind) {
  case ValueKind::number:
    return "number";
  case ValueKind::integer:
    return "integer";
  case ValueKind::boolean:
    return "boolean";
  case ValueKind::string:
    return "string";
  case ValueKind::numbers:
    return k.count > 0 ? std::to_string(k.count) + " numbers" : "numbers";
  case ValueKind::time_function:
    return "function";
  case ValueKind::table:
    return "table";
  case ValueKind::tables:
    return "array of tables";
  case ValueKind::named_tables:
    return "tables by name";
  case ValueKind::strings:
    return "array of strings";
  case ValueKind::any:
    break;
  }
  return "see meaning";
}

/// Range or choices, as one phrase.
std::string allowed(const KeySpec& k) {
  if (!k.choices.empty()) {
    std::string list;
    for (const std::string& c : k.choices) {
      list += (list.empty() ? "" : ", ") + ("\"" + c + "\"");
    }
    return list;
  }
  return k.range_text();
}

std::string material_range(const MaterialParameterSpec& p) {
  return p.range.text();
}

std::string material_default(const MaterialParameterSpec& p) {
  return p.default_value ? format_bound(*p.default_value) : "required";
}

std::string strip_brackets(std::string name) {
  name.erase(std::remove_if(name.begin(), name.end(), [](char c) { return c == '[' || c == ']'; }),
             name.end());
  return name;
}

void describe_material(const MaterialType& type, std::ostream& out) {
  out << "[materials.<name>] with type = \"" << type.name << "\": " << type.description << '\n';
  for (const MaterialParameterSpec& p : type.parameters) {
    out << "  " << p.name << "  (number" << (p.unit.empty() ? "" : ", " + p.unit) << "; default "
        << material_default(p);
    if (!material_range(p).empty()) {
      out << "; " << material_range(p);
    }
    out << ")\n      " << p.meaning << '\n';
  }
}

void describe_table(const TableSpec& t, std::ostream& out) {
  out << table_heading(t) << ": " << t.meaning << '\n';
  for (const KeySpec& k : t.keys) {
    out << "  " << k.name << "  (" << kind_name(k) << (k.unit.empty() ? "" : ", " + k.unit)
        << "; default " << k.default_description();
    if (!allowed(k).empty()) {
      out << "; " << allowed(k);
    }
    out << ")\n      " << k.meaning << '\n';
  }
  if (t.material_parameters) {
    out << "  and the parameters of its type: mpile describe <type> (";
    std::string names;
    for (const MaterialType& type : material_types()) {
      names += (names.empty() ? "" : ", ") + type.name;
    }
    out << names << ")\n";
  }
}

std::string cell(std::string text) {
  // A Markdown table cell: pipes would split it.
  std::string out;
  for (const char c : text) {
    if (c == '|') {
      out += "\\|";
    } else {
      out += c;
    }
  }
  return out;
}

std::string code(const std::string& s) {
  return "`" + s + "`";
}

std::string markdown_table(const TableSpec& t) {
  std::ostringstream out;
  out << "| key | type | unit | default | allowed | meaning |\n|---|---|---|---|---|---|\n";
  for (const KeySpec& k : t.keys) {
    const std::string d = k.default_description();
    const bool literal = d != "required" && d != "none" && k.default_text.empty();
    out << "| " << code(k.name) << " | " << kind_name(k) << " | " << cell(k.unit) << " | "
        << (literal ? code(d) : d) << " | " << cell(allowed(k)) << " | " << cell(k.meaning)
        << " |\n";
  }
  return out.str();
}

std::string markdown_material(const MaterialType& type) {
  std::ostringstream out;
  out << "| parameter | unit | default | allowed | meaning |\n|---|---|---|---|---|\n";
  for (const MaterialParameterSpec& p : type.parameters) {
    const std::string d = material_default(p);
    out << "| " << code(p.name) << " | " << cell(p.unit) << " | " << (d == "required" ? d : code(d))
        << " | " << cell(material_range(p)) << " | " << cell(p.meaning) << " |\n";
  }
  return out.str();
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
    case '"':
      out += "\\\"";
      break;
    case '\\':
      out += "\\\\";
      break;
    case '\n':
      out += "\\n";
      break;
    default:
      out += c;
    }
  }
  return out + "\"";
}

std::string json_number(double x) {
  return format_bound(x);
}

void json_bounds(const ParameterRange& r, std::vector<std::string>& fields) {
  if (r.lower) {
    fields.push_back(json_string(r.lower->inclusive ? "minimum" : "exclusiveMinimum") + ": " +
                     json_number(r.lower->value));
  }
  if (r.upper) {
    fields.push_back(json_string(r.upper->inclusive ? "maximum" : "exclusiveMaximum") + ": " +
                     json_number(r.upper->value));
  }
}

std::string json_object(const std::vector<std::string>& fields) {
  std::string out = "{";
  for (std::size_t i = 0; i < fields.size(); ++i) {
    out += (i == 0 ? "" : ", ") + fields[i];
  }
  return out + "}";
}

std::string json_choices(const std::vector<std::string>& choices) {
  std::string out = "[";
  for (std::size_t i = 0; i < choices.size(); ++i) {
    out += (i == 0 ? "" : ", ") + json_string(choices[i]);
  }
  return out + "]";
}

std::string describe_key(const KeySpec& k) {
  std::string d = k.meaning;
  if (!k.unit.empty() && k.unit != "-") {
    d += " [" + k.unit + "]";
  }
  return d + "; default " + k.default_description();
}

std::string schema_of_table(const TableSpec& t);

std::string schema_of_key(const TableSpec& owner, const KeySpec& k) {
  std::vector<std::string> f{json_string("description") + ": " + json_string(describe_key(k))};
  const std::string child_path = owner.path.empty() ? k.name : owner.path + "." + k.name;
  auto child = [&](const std::string& path) -> const TableSpec& {
    const TableSpec* spec = find_table_spec(path);
    if (spec == nullptr) {
      throw std::logic_error("no declaration of the table " + path);
    }
    return *spec;
  };
  switch (k.kind) {
  case ValueKind::number:
  case ValueKind::integer:
    f.push_back(json_string("type") + ": " +
                json_string(k.kind == ValueKind::number ? "number" : "integer"));
    json_bounds(k.range, f);
    if (const double* x = std::get_if<double>(&k.fallback)) {
      f.push_back(json_string("default") + ": " + json_number(*x));
    }
    if (const long* x = std::get_if<long>(&k.fallback)) {
      f.push_back(json_string("default") + ": " + std::to_string(*x));
    }
    break;
  case ValueKind::boolean:
    f.push_back(json_string("type") + ": " + json_string("boolean"));
    if (const bool* x = std::get_if<bool>(&k.fallback)) {
      f.push_back(json_string("default") + ": " + (*x ? "true" : "false"));
    }
    break;
  case ValueKind::string:
    f.push_back(json_string("type") + ": " + json_string("string"));
    if (!k.choices.empty()) {
      f.push_back(json_string("enum") + ": " + json_choices(k.choices));
    }
    if (const std::string* x = std::get_if<std::string>(&k.fallback)) {
      f.push_back(json_string("default") + ": " + json_string(*x));
    }
    break;
  case ValueKind::numbers:
    f.push_back(json_string("type") + ": " + json_string("array"));
    f.push_back(json_string("items") + ": " +
                json_object({json_string("type") + ": " + json_string("number")}));
    if (k.count > 0) {
      f.push_back(json_string("minItems") + ": " + std::to_string(k.count));
      f.push_back(json_string("maxItems") + ": " + std::to_string(k.count));
    }
    break;
  case ValueKind::strings:
    f.push_back(json_string("type") + ": " + json_string("array"));
    f.push_back(json_string("items") + ": " +
                json_object({json_string("type") + ": " + json_string("string"),
                             json_string("enum") + ": " + json_choices(k.choices)}));
    break;
  case ValueKind::time_function:
    f.push_back(json_string("anyOf") + ": [" +
                json_object({json_string("type") + ": " + json_string("number")}) + ", " +
                json_object({json_string("$ref") + ": " + json_string("#/$defs/time_function")}) +
                "]");
    break;
  case ValueKind::table:
    return schema_of_table(child(child_path));
  case ValueKind::tables:
    f.push_back(json_string("type") + ": " + json_string("array"));
    f.push_back(json_string("items") + ": " + schema_of_table(child(child_path)));
    break;
  case ValueKind::named_tables:
    f.push_back(json_string("type") + ": " + json_string("object"));
    f.push_back(json_string("additionalProperties") + ": " +
                schema_of_table(child(child_path + ".*")));
    break;
  case ValueKind::any:
    if (const TableSpec* spec = find_table_spec(child_path)) {
      // A string, an array or this table (contact.surfaces): the table's keys are checked.
      f.push_back(json_string("if") + ": " +
                  json_object({json_string("type") + ": " + json_string("object")}));
      f.push_back(json_string("then") + ": " + schema_of_table(*spec));
    }
    break;
  }
  return json_object(f);
}

std::string schema_of_table(const TableSpec& t) {
  std::vector<std::string> properties;
  for (const KeySpec& k : t.keys) {
    properties.push_back(json_string(k.name) + ": " + schema_of_key(t, k));
  }
  std::vector<std::string> conditions;
  if (t.material_parameters) {
    // Every type's parameters are allowed; a type's required ones are required with it.
    std::set<std::string> seen;
    for (const MaterialType& type : material_types()) {
      std::vector<std::string> required;
      for (const MaterialParameterSpec& p : type.parameters) {
        if (!p.default_value) {
          required.push_back(p.name);
        }
        if (seen.insert(p.name).second) {
          std::vector<std::string> f{json_string("type") + ": " + json_string("number"),
                                     json_string("description") + ": " +
                                         json_string(p.meaning + " [" + p.unit + "]")};
          properties.push_back(json_string(p.name) + ": " + json_object(f));
        }
      }
      conditions.push_back(json_object(
          {json_string("if") + ": " +
               json_object({json_string("properties") + ": " +
                            json_object({json_string("type") + ": " +
                                         json_object({json_string("const") + ": " +
                                                      json_string(type.name)})})}),
           json_string("then") + ": " +
               json_object({json_string("required") + ": " + json_choices(required)})}));
    }
  }
  std::vector<std::string> f{json_string("type") + ": " + json_string("object"),
                             json_string("description") + ": " + json_string(t.meaning),
                             json_string("properties") + ": " + json_object(properties),
                             json_string("additionalProperties") + ": false"};
  if (!conditions.empty()) {
    f.push_back(json_string("allOf") + ": [" + [&] {
      std::string s;
      for (std::size_t i = 0; i < conditions.size(); ++i) {
        s += (i == 0 ? "" : ", ") + conditions[i];
      }
      return s;
    }() + "]");
  }
  return json_object(f);
}

std::string table_list() {
  std::string list;
  for (const TableSpec& t : case_format()) {
    list += (list.empty() ? "" : ", ") + (t.path.empty() ? std::string("top") : t.path);
  }
  for (const MaterialType& type : material_types()) {
    list += ", " + type.name;
  }
  return list;
}

} // namespace

std::string describe_tables(const std::string& table) {
  std::ostringstream out;
  const std::string wanted = strip_brackets(table);
  if (wanted.empty() || wanted == "all") {
    for (const TableSpec& t : case_format()) {
      describe_table(t, out);
      out << '\n';
    }
    for (const MaterialType& type : material_types()) {
      describe_material(type, out);
      out << '\n';
    }
    return out.str();
  }
  const std::string path = wanted == "top" ? "" : wanted;
  if (const TableSpec* t = find_table_spec(path == "materials.<name>" ? "materials.*" : path)) {
    describe_table(*t, out);
    return out.str();
  }
  for (const MaterialType& type : material_types()) {
    if (type.name == wanted) {
      describe_material(type, out);
      return out.str();
    }
  }
  throw CaseError("no table or material type '" + table + "' (the format has " + table_list() +
                  ")");
}

std::string case_json_schema() {
  const TableSpec& top = *find_table_spec("");
  const TableSpec& function = *find_table_spec("time_function");
  std::string schema = schema_of_table(top);
  // The root object with the schema's own keys first.
  schema.erase(0, 1);
  return "{" + json_string("$schema") + ": " +
         json_string("https://json-schema.org/draft/2020-12/schema") + ", " + json_string("title") +
         ": " + json_string("mpile case file") + ", " + json_string("$defs") + ": " +
         json_object({json_string("time_function") + ": " + schema_of_table(function)}) + ", " +
         schema + "\n";
}

std::string regenerate_doc(const std::string& text, const std::string& file) {
  std::istringstream in(text);
  std::ostringstream out;
  std::string line;
  std::set<std::string> shown_tables, shown_materials;
  int number = 0;
  bool skipping = false;
  std::string end_marker;
  while (std::getline(in, line)) {
    ++number;
    if (skipping) {
      if (line == end_marker) {
        out << line << '\n';
        skipping = false;
      }
      continue;
    }
    out << line << '\n';
    const std::string keys = "<!-- keys ", material = "<!-- material ", close = " -->";
    const bool is_keys = line.rfind(keys, 0) == 0;
    const bool is_material = line.rfind(material, 0) == 0;
    if (!is_keys && !is_material) {
      continue;
    }
    const std::size_t start = is_keys ? keys.size() : material.size();
    if (line.size() < start + close.size() ||
        line.compare(line.size() - close.size(), close.size(), close) != 0) {
      throw CaseError(file + ":" + std::to_string(number) +
                      ": a generated block's marker must "
                      "end with -->");
    }
    const std::string name = line.substr(start, line.size() - start - close.size());
    if (is_keys) {
      const TableSpec* t = find_table_spec(name == "top" ? "" : name);
      if (t == nullptr) {
        throw CaseError(file + ":" + std::to_string(number) + ": no table '" + name +
                        "' in cases/case_format.cpp");
      }
      shown_tables.insert(t->path);
      out << markdown_table(*t);
      end_marker = "<!-- end keys -->";
    } else {
      const auto& types = material_types();
      const auto type = std::find_if(types.begin(), types.end(),
                                     [&](const MaterialType& m) { return m.name == name; });
      if (type == types.end()) {
        throw CaseError(file + ":" + std::to_string(number) + ": no material type '" + name + "'");
      }
      shown_materials.insert(name);
      out << markdown_material(*type);
      end_marker = "<!-- end material -->";
    }
    skipping = true;
  }
  if (skipping) {
    throw CaseError(file + ": a generated block has no " + end_marker);
  }
  for (const TableSpec& t : case_format()) {
    if (!shown_tables.contains(t.path)) {
      throw CaseError(file + ": no generated block shows " + table_heading(t) + " (add <!-- keys " +
                      (t.path.empty() ? std::string("top") : t.path) +
                      " --> and <!-- end keys -->)");
    }
  }
  for (const MaterialType& type : material_types()) {
    if (!shown_materials.contains(type.name)) {
      throw CaseError(file + ": no generated block shows the material type " + type.name);
    }
  }
  return out.str();
}

int describe_command(const DescribeOptions& options, std::ostream& out, std::ostream& err) {
  try {
    if (!options.update_doc.empty() || !options.check_doc.empty()) {
      const std::string& path = options.update_doc.empty() ? options.check_doc : options.update_doc;
      // A regular file only: /dev/zero was read without end, a FIFO would block.
      std::error_code not_regular;
      if (!std::filesystem::is_regular_file(path, not_regular)) {
        err << "mpile describe: " << path << ": not a regular file (a Markdown page)\n";
        return exit_bad_input;
      }
      std::ifstream in(path);
      if (!in) {
        err << "mpile describe: cannot read " << path << '\n';
        return exit_bad_input;
      }
      std::ostringstream text;
      text << in.rdbuf();
      const std::string fresh = regenerate_doc(text.str(), path);
      if (!options.check_doc.empty()) {
        if (fresh != text.str()) {
          err << path
              << " is stale: its key tables differ from cases/case_format.cpp; run mpile "
                 "describe --update-doc "
              << path << '\n';
          return exit_failure;
        }
        out << path << " is up to date\n";
        return exit_success;
      }
      std::ofstream write(path);
      write << fresh;
      if (!write) {
        err << "mpile describe: cannot write " << path << '\n';
        return exit_failure;
      }
      out << "rewrote the key tables of " << path << '\n';
      return exit_success;
    }
    if (options.json_schema) {
      out << case_json_schema();
      return exit_success;
    }
    out << describe_tables(options.table);
    return exit_success;
  } catch (const CaseError& e) {
    err << "mpile describe: " << e.what() << '\n';
    return exit_bad_input;
  }
}

} // namespace mpile
