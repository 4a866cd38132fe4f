#include "render/renderer.h"

#include <string>

#include "core/names.h"
#include "soft/raster.h"

namespace shadowvol {
std::string_view to_string(Method method) {
  switch (method) {
    case Method::zpass:
      return "zpass";
    case Method::zfail:
      return "zfail";
    case Method::automatic:
      return "auto";
    case Method::split_plane:
      return "spsv";
    case Method::zpass_prefill:
      return "zp+db";
  }
  return "unknown";
}

Expected<Method> parse_method(std::string_view name) {
  return parse_name(
      name,
      {Method::zpass, Method::zfail, Method::automatic, Method::split_plane, Method::zpass_prefill},
      "method");
}

std::string_view to_string(Extrusion extrusion) {
  return extrusion == Extrusion::infinite ? "infinite" : "bounded";
}

Expected<Extrusion> parse_extrusion(std::string_view name) {
  return parse_name(name, {Extrusion::infinite, Extrusion::bounded}, "extrusion");
}

std::string_view to_string(SplitPlanes planes) {
  return planes == SplitPlanes::laine ? "laine" : "sampled";
}

Expected<SplitPlanes> parse_split_planes(std::string_view name) {
  return parse_name(name, {SplitPlanes::laine, SplitPlanes::sampled}, "split-plane construction");
}

std::string_view to_string(SplitParts parts) {
  return parts == SplitParts::each ? "each" : "whole";
}

Expected<SplitParts> parse_split_parts(std::string_view name) {
  return parse_name(name, {SplitParts::each, SplitParts::whole}, "split-plane decomposition");
}

Expected<void> check_options(const RenderOptions& options) {
  if (options.width < 1 || options.height < 1 || options.width > soft::kMaxViewport ||
      options.height > soft::kMaxViewport)
    return make_error("image size " + std::to_string(options.width) + "x" +
                      std::to_string(options.height) + " is outside 1x1 .. " +
                      std::to_string(soft::kMaxViewport) + "x" +
                      std::to_string(soft::kMaxViewport));
  return {};
}

}  // namespace shadowvol
