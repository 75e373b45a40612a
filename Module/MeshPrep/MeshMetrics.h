#ifndef catarMeshMetrics_h
#define catarMeshMetrics_h
#include "TriangleMesh.h"
#endif
