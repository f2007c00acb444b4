// The batch kernel of spherical-triangle sampling (core/spherical_triangle_batch.cpp): sample_spherical_triangle for
// up to kChunk receivers, each with its own triangle, by column.
#pragma once

namespace lumis::sph_tri {

struct Batch {
  static constexpr int kChunk = 64;
  float px[kChunk], py[kChunk], pz[kChunk];                    // in: receivers
  float ax[kChunk], ay[kChunk], az[kChunk];                    //     triangle corners
  float bx[kChunk], by[kChunk], bz[kChunk];
  float cx[kChunk], cy[kChunk], cz[kChunk];
  float ux[kChunk], uy[kChunk];                                //     2D samples
  float wx[kChunk], wy[kChunk], wz[kChunk], pdf[kChunk];       // out: direction (world), density (solid angle)
  int ok[kChunk];                                              //      sampling by solid angle works (else ignore)
};

/// Fill the outputs of b's first n lanes with the kernel at `level` (simd_level() or below; tests try each).
void run(Batch& b, int n, int level);

}  // namespace lumis::sph_tri
