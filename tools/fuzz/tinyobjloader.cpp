// tinyobjloader's implementation, compiled here so that the fuzz build instruments its parser (coverage and
// ASan); the other presets link Debian's libtinyobjloader, built from this same header.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
