// Temporal accumulation, shared by the radiosity and AO temporal filters.
//
// Each frame's gather takes a new point of a sequence that never repeats
// (temporal_sequence.h), so the frames are independent-ish samples of the
// integral the gather estimates and their mean converges to it. Per pixel
// the history holds the filtered mean and, in the history key's w, the
// number n of frames it stands for. The history weight is
//   still pixel:  n / (n + 1), n capped at DEEPGI_TEMPORAL_CAP - 1:
//                 the running mean of all frames, then of the last ~CAP;
//   moving pixel: min(n / (n + 1), alpha): the exponential blend, whose
//                 history stands for 1 / (1 - alpha) frames, so n is capped
//                 there and a camera that stops resumes the running mean
//                 at about the weight it had, with no jump.
// A pixel is still when its motion vector is below 1/64 pixel
// (history_reprojection.glsl). alpha <= 0 turns the filter off (the raw
// result). Why the cap, and what it costs, in docs/radiosity.md.

struct Accumulation {
  vec4 mean;
  float count;
};

Accumulation accumulate(vec4 raw, vec4 mean, float count, float alpha, bool still) {
  if (alpha <= 0.0) return Accumulation(raw, 0.0);
  float n = still ? min(count, float(DEEPGI_TEMPORAL_CAP - 1)) : count;
  float history_weight = n / (n + 1.0);
  if (!still) history_weight = min(history_weight, alpha);
  Accumulation result;
  result.mean = mix(raw, mean, history_weight);
  result.count = still ? n + 1.0 : min(n + 1.0, 1.0 / (1.0 - alpha));
  return result;
}
