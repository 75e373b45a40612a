#ifndef catarScreenSpaceRemeshing_h
#define catarScreenSpaceRemeshing_h
#include "TriangleMesh.h"
#endif
