#pragma once
// The cad plugin's exported entry points (libconform_cad.so), found by core with Plugin::symbol(). Declared here so
// that their types are checked against the interface core uses (conform_cad_read_fn, conform_cad_free_fn).

#include "conform/core/cad_plugin_abi.h"

extern "C" {
__attribute__((visibility("default"))) int conform_cad_read(const conform_cad_request* request,
                                                             conform_cad_result* result);
__attribute__((visibility("default"))) void conform_cad_free(conform_cad_result* result);
}
