#ifndef catarPointSetSurface_h
#define catarPointSetSurface_h
#include "TriangleMesh.h"
#endif
