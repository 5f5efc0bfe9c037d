#pragma once
// Pieces of render_html shared by its source files (not public API).

#include <string>
#include <string_view>
#include <vector>

#include "conform/report/page.h"

namespace conform::html::detail {

// Text safe inside HTML elements and double-quoted attributes.
std::string escape_html(std::string_view text);
// Standard base64 (RFC 4648, with padding).
std::string base64(std::string_view bytes);
// A number as text: "%.*g" with `digits` significant digits, "NaN" / "inf" spelled out.
std::string format_g(double value, int digits);

// The <svg> element of a plot.
std::string plot_svg(const Plot& plot);
// The colour bar's <svg>.
std::string colour_bar_svg(const ColourBar& bar);
// The scene as the JSON object the page's script reads (origin, objects with base64 little-endian arrays);
// `thinned` is scene.thinned().
std::string scene_json(const Scene& scene, const std::vector<SceneObject>& thinned);

// The page's stylesheet and its viewer script (viewer_assets.cpp), and libjs-three (generated).
const char* page_css();
const char* viewer_js();
std::string three_min_js();
std::string orbit_controls_js();

}  // namespace conform::html::detail
