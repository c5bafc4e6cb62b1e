// How many frames a pixel's means hold: its history. Without reprojection every pixel's is the
// number of frames since the last restart. When the camera moves and the reproject stage carries
// each pixel's history to where its surface is now seen (reproject.h), pixels differ: a surface
// that came into view starts again, one that stayed in view keeps its frames. The auxiliary
// images keep the count (PixelAov::frames, written by the accumulate stage), so pixels have their
// own only where those are kept (FLAG_AOVS, which reprojection implies).
#ifndef PHOTON_SHARED_HISTORY_H
#define PHOTON_SHARED_HISTORY_H

#include "bindings.h"

PH_NAMESPACE_BEGIN

// The frames already in the pixel's means, before this frame's.
PH_FN uint historyFrames(BUF_PARAM uint pixel) {
    uint n = BUF(params).accumulated;
    if (n > 0u && (BUF(params).flags & FLAG_AOVS) != 0u) {
        n = uint(BUF(aovs)[pixel].frames);
    }
    return n;
}

PH_NAMESPACE_END

#endif
