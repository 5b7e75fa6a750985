// SPDX-License-Identifier: MIT
// OpenGL 3.3 core declarations. Linux's libGL (glvnd) exports every core entry point, so the
// prototypes are declared directly and no loader is needed.
#pragma once

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
