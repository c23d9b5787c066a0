// Must NOT compile: compiled as part of the render layer, it reaches up into techniques (the
// render/techniques cycle the registry once made).
#include "bounce/techniques/registry.h"
