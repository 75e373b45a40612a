#ifndef catarRemeshing_h
#define catarRemeshing_h
#include "TriangleMesh.h"
#endif
