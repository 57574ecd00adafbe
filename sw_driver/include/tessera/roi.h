/* The region of interest: the part of a run an application wants measured
 * apart, as gem5's m5_work_begin/end mark one. Everything between
 * tessera_roi_begin() and tessera_roi_end() is reported, besides the whole
 * run's statistics, in stats.json's "roi": the growth of every statistic
 * that accumulates (times, counts, cycles, bytes, energy) summed over the
 * regions, their count, the first begin and the last end, and the frames
 * whose eglSwapBuffers fell in one (docs/usage.md, "Region of interest").
 *
 * Each call is one store to the SoC's simulation control register
 * (sim_control in the memory map): a few host cycles, on the host-compiled
 * model and on the ISS alike. A begin inside a region and an end outside
 * one change nothing; a region still open when the run ends ends with it. */
#ifndef TESSERA_ROI_H
#define TESSERA_ROI_H

#ifdef __cplusplus
extern "C" {
#endif

__attribute__((visibility("default"))) void tessera_roi_begin(void);
__attribute__((visibility("default"))) void tessera_roi_end(void);

#ifdef __cplusplus
}
#endif

#endif
