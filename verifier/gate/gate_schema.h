// The gate file's JSON Schema (verifier/gate/gate_schema.json), compiled in: the loader applies it to every gate
// file (verifier/gate/gate_file.cpp), `hpsf check --schema` prints it for editors and CI linters, and it is
// installed beside the headers.
#ifndef HPSF_VERIFIER_GATE_GATE_SCHEMA_H
#define HPSF_VERIFIER_GATE_GATE_SCHEMA_H

namespace hpsf {

extern const char* const kGateSchemaJson;

}  // namespace hpsf

#endif  // HPSF_VERIFIER_GATE_GATE_SCHEMA_H
