// Temporal accumulation over whole rotation cycles, shared by the radiosity
// and AO temporal filters.
//
// The gather patterns rotate through DEEPGI_TEMPORAL_CYCLE (P) angles and
// repeat (frame.cpp). Per pixel the history holds
//   mean:    the filtered result,
//   partial: the running mean of the frames of the current cycle so far,
//   count:   frames accumulated (in the history key's w), capped at 255.
// While a pixel has fewer than P frames, mean is the running mean of all of
// them (history weight n / (n + 1)): a disoccluded pixel converges as fast as
// plain averaging allows. From then on mean changes only when a cycle ends,
// to mean + (1 - alpha^P) * (cycle mean - mean): alpha^P per cycle forgets
// old light as fast as a per-frame blend with weight alpha would. Why this converges under a
// static camera: each cycle sees the same P patterns, so with unchanging
// inputs every cycle mean is the same number, bit for bit (same operations on
// the same values), and mean stops moving once it holds it; a plain
// exponential blend of a rotating pattern instead keeps moving by
// (1 - alpha) * (this frame's pattern - mean) forever. With bounces
// (rho_prop > 0) the inputs themselves converge geometrically, and so does
// mean. alpha <= 0 turns the filter off (the raw result).

struct Accumulation {
  vec4 mean;
  vec4 partial;
  float count;
};

Accumulation accumulate(vec4 raw, vec4 mean, vec4 partial, float count, float alpha) {
  if (alpha <= 0.0) return Accumulation(raw, raw, 0.0);
  int n = int(count);
  int phase = frame.temporal_phase;
  // Frames of the current cycle this pixel's partial mean already holds.
  int in_cycle = min(n, phase);
  Accumulation result;
  result.partial = in_cycle == 0 ? raw : partial + (raw - partial) / float(in_cycle + 1);
  if (n < DEEPGI_TEMPORAL_CYCLE) {
    result.mean = n == 0 ? raw : mean + (raw - mean) / float(n + 1);
  } else if (phase == DEEPGI_TEMPORAL_CYCLE - 1) {
    // n >= P > phase, so partial covers the whole cycle that ends now.
    result.mean = mean + (result.partial - mean) * (1.0 - pow(alpha, float(DEEPGI_TEMPORAL_CYCLE)));
  } else {
    result.mean = mean;
  }
  result.count = float(min(n + 1, 255));
  return result;
}
