// The rotated-grid MIP chain of depth_pyramid.comp and radiosity_prepare.comp:
// texel t of level m + 1 copies texel 2t + corner(t) of level m, the corner
// alternating with the parity of the other axis (odd sizes clamp).

ivec2 rotated_grid_corner(ivec2 texel) { return ivec2((texel.y & 1) ^ 1, (texel.x & 1) ^ 1); }

// The level-0 pixel whose values texel `texel` of `level` holds, for a
// level-0 size `size`.
ivec2 rotated_grid_source_pixel(ivec2 texel, int level, ivec2 size) {
  for (int l = level; l > 0; --l) {
    texel = min(2 * texel + rotated_grid_corner(texel), max(size >> (l - 1), ivec2(1)) - 1);
  }
  return texel;
}
