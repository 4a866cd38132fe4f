// shadowvol accel: the slicing planes of discrete shadow clamping (Lloyd, Wendt, Govindaraju and
// Manocha 2004, "CC Shadow Volumes", §3.2.2).
//
// Owns: where the planes lie. They pass through the eye, so each is a line on the image and the
// caps a volume would have on them cover no pixel (§3.3: "no caps need to be drawn"); they face
// the light: the lines run across the way shadows run on the image, and split it into strips of
// equal width. A volume drawn between two of them is the volume cut to a strip of the image, as
// projecting its silhouette edges onto both planes would make it. Drawn whole and kept to the
// strip pixel by pixel (raster::ScreenStrip; a fragment test on the GPU), it needs no special
// case for edges that no plane ahead of them meets (the paper extrudes those to infinity from the
// last plane they reach), and its light caps keep the depths of their surfaces, which cutting
// them would not.
//
// Direction: a point p of the image (NDC) in shadow of a light L (clip space, homogeneous: w = 0
// for a directional light) moves, as it slides away from the light, along L.w p - L.xy (the
// derivative of the projection of p + t (p - L)); the strips run across that at the image's
// centre, -L.xy, which is all one direction when the light lies outside the view, the paper's
// case (the strips work for any light; they cut less where the directions spread).
//
// Conservative (§3.2.3): a pixel belongs to every strip whose band, widened by a pixel and a half
// on each side, holds its centre, so that a centre in a volume's shadow lies at least that far
// inside the strips it is drawn in, beyond any rounding of the clipped edges.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "accel/light_views.h"
#include "raster/raster.h"

namespace shadowvol {

struct Slices {
  glm::dvec2 across{1.0, 0.0};       // unit, NDC: the strips' coordinate s = across . ndc
  double first = -1.0, width = 0.0;  // strip k is s in [first + k width, first + (k + 1) width]
  int count = 0;
  double margin = 0.0;  // a pixel and a half, in s

  // The strips whose widened bands hold s, or the range [lo, hi] of s.
  LayerRange of(double lo, double hi) const;
  LayerRange of(double s) const { return of(s, s); }
  // Strips [first_strip, last_strip] as one raster::ScreenStrip, unbounded at the image's edges.
  raster::ScreenStrip strip(int first_strip, int last_strip) const;
};

// `count` slices of a width x height image of `view_proj` for `light` (eye-relative,
// homogeneous).
Slices make_slices(const glm::mat4& view_proj, const glm::vec4& light, int width, int height,
                   int count);

}  // namespace shadowvol
