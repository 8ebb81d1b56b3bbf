#pragma once
// Reference (calibration) plates at the ends of a laser texture record: a profilometer's record
// often starts and ends on a flat plate of known height, which is not road and must not enter
// the MPD (ISO 13473-1 evaluates the pavement only).
//
// A plate is a run at the start (or end) of the record, at least `min_length` long, whose valid
// samples stay within `flatness` (max - min) of each other, and whose level differs from the
// median of the rest of the record by at least `min_step`: flat and standing apart from the
// road, which a road's texture (never flat to 0.2 mm over 10 mm) or a smooth road at its own
// level is not. The cut goes `margin` beyond the run, over the plate's edge.
#include <cstddef>

namespace wr {

struct PlateOptions {
  double min_length = 10e-3;  // m
  double flatness = 0.2e-3;   // m, max - min of the plate's samples
  double min_step = 2e-3;     // m, plate level against the road's median
  double margin = 2e-3;       // m, cut beyond the plate
};

struct PlateCut {
  std::size_t start = 0, end = 0;  // samples to drop at the start and at the end
};

// Samples of the n (dx apart) that lie on plates; `dropout` samples are skipped in the tests.
// Nothing is cut from a record that would keep less than a quarter of its samples.
PlateCut find_reference_plates(const double* h, const unsigned char* dropout, std::size_t n, double dx,
                               const PlateOptions& opt = {});

}  // namespace wr
