#version 460
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
layout(local_size_x = 8, local_size_y = 8) in;
void main() {}
