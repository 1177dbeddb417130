#include "gpu/gpu_layout.h"
