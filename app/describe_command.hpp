#pragma once

// `mpile describe`: the case format's declaration (cases/case_format.hpp) as text for the terminal,
// as the key tables of docs/case-format.md, and as a JSON Schema for TOML editors.

#include <iosfwd>
#include <string>

namespace mpile {

struct DescribeOptions {
  std::string table;        // one table ("solver", "[[phases]]", "phases.stop_at", a material type)
  bool json_schema = false; // print the JSON Schema instead
  std::string update_doc;   // rewrite the generated blocks of this Markdown file
  std::string check_doc;    // exit 1 when this Markdown file's generated blocks are stale
};

/// Every key of `table` (all tables when empty) with its type, unit, default, range and meaning.
/// Throws CaseError for a table the format does not have, listing those it has.
std::string describe_tables(const std::string& table);

/// The JSON Schema (draft 2020-12) of a case file. Required keys are not marked required: a case
/// may take them from its base file.
std::string case_json_schema();

/// `text` with every generated block rewritten: between `<!-- keys PATH -->` and
/// `<!-- end keys -->` the key table of PATH, between `<!-- material TYPE -->` and
/// `<!-- end material -->` the parameters of that material type. Throws CaseError for a block
/// naming nothing declared, and for a declared table or material type no block shows.
std::string regenerate_doc(const std::string& text, const std::string& file);

int describe_command(const DescribeOptions& options, std::ostream& out, std::ostream& err);

} // namespace mpile
