// The surface clip's one test, shared by the indicator pass's vertex stage
// (the spot's centre) and its fragment stage (each fragment's own pixel):
// does the scene show the spot's own surface at depth texel `texel`, where
// the quad's point has 1 / w = inv_w? Include after the push constants.
//
// The scene's depth there gives the point the eye sees along the same ray;
// that point must lie in the spot's plane, which the quad floats
// SP_INDICATOR_LIFT above. A wall beyond an edge, a face round a corner or
// the floor far below all lie off that plane, however close in depth. The
// tolerance covers depth precision and a triangle's own rounding: 1 cm +
// 0.2 % of the distance.
//
// The point seen is eye + (q - eye) * s, s = scene distance / q's distance
// = depth_b * inv_w / (depth + depth_a) (view distance scales linearly along
// the ray). As q lies in the quad's plane, its height above the surface's
// plane is h * (s - 1) + lift, where h = dot(anchor - eye, normal), the
// eye's height over the plane, is one number per spot. Both sides of the
// test are multiplied by inv_w (> 0) to spare a division.
bool sp_on_spot_surface(ivec2 texel, float inv_w, float plane_depth) {
  float depth = texelFetch(scene_depth, texel, 0).r;
  float s = push.depth_b * inv_w / (depth + push.depth_a);
  float off_plane = plane_depth * (s - 1.0) + SP_INDICATOR_LIFT;
  return abs(off_plane) * inv_w <= 0.01 * inv_w + 0.002;
}
