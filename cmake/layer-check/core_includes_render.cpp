// Must NOT compile: compiled as part of the core layer, it reaches up into render.
#include "bounce/render/renderer.h"
