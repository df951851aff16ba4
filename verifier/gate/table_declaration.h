// A table declared, not coded (docs/reference/table-declaration.md): a small versioned JSON file that gives a
// table's probing scheme, key identity, sums and passes. `--table FILE` applies it to the filter's options; hpsf's
// own table is one declaration among others (examples/tables/hpsf.json).
#ifndef HPSF_VERIFIER_GATE_TABLE_DECLARATION_H
#define HPSF_VERIFIER_GATE_TABLE_DECLARATION_H

#include <string>
#include <vector>

#include "core/filter_config.h"

namespace hpsf {

extern const char* const kTableSchemaJson;  // verifier/gate/table_schema.json, compiled in

// A setting the declaration made: where in the file, and the command-line option it stands for.
struct DeclaredSetting {
  std::string pointer;  // a JSON pointer into the declaration, such as "/probing"
  std::string option;   // such as "--probing"
};

// Reads the declaration at `path` and applies it to `config`, which keeps what the declaration leaves out. Returns
// the settings it made. Bad input (unreadable, not JSON, off the schema, or a value the filter rejects) is an
// InputError naming the file and the place in it.
std::vector<DeclaredSetting> ApplyTableDeclaration(const std::string& path, FilterConfig& config);

// The same for a declaration's text; `source` names it in errors.
std::vector<DeclaredSetting> ApplyTableDeclarationText(const std::string& text, const std::string& source,
                                                       FilterConfig& config);

// The declaration of `config`'s table, every field given: what hpsf writes into a capture of its own runs. Applied
// to hpsf's defaults, it gives back config's table (capacity, probing, key, sums and passes).
std::string TableDeclarationText(const FilterConfig& config);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_GATE_TABLE_DECLARATION_H
