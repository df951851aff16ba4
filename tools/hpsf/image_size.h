// `--size WIDTHxHEIGHT`, as render and crosscheck both take it.
#ifndef HPSF_TOOLS_HPSF_IMAGE_SIZE_H
#define HPSF_TOOLS_HPSF_IMAGE_SIZE_H

#include <string>

#include "tracer/path_tracer.h"

namespace hpsf {

// Sets trace.width and trace.height; ConfigError naming --size otherwise.
void ParseSize(const std::string& text, TraceOptions& trace);

}  // namespace hpsf

#endif  // HPSF_TOOLS_HPSF_IMAGE_SIZE_H
