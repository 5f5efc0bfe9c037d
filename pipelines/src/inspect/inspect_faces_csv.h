#pragma once
// `conform inspect --out-faces FILE.csv`: one row per CAD face, the figures of the JSON's `faces` (empty cells where a
// figure does not apply or was not measured).

#include "conform/core/csv.h"
#include "conform/pipelines/inspect/inspect.h"

namespace conform::detail {

CsvWriter faces_csv(const InspectResult& result);

}  // namespace conform::detail
