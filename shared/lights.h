// Lights: photon emission (emission.h: the global pass samples each light's own distribution;
// caustic_aiming.h: the caustic pass aims at specular objects, after Jensen's projection maps)
// and direct-light sampling for the eye pass (direct_light.h), over the sources all share
// (light_sources.h). Emitted power and sampled radiance come from the same intensity functions,
// so direct light and photon estimates always agree on how bright a light is.
#ifndef PHOTON_SHARED_LIGHTS_H
#define PHOTON_SHARED_LIGHTS_H

#include "caustic_aiming.h"
#include "direct_light.h"
#include "emission.h"
#include "light_sources.h"

#endif
