// Must compile: what a lab may include (the control for the four probes beside it).
#include "lab_app.h"
#include "mesh.h"
#include "pipeline_builder.h"
#include "scene.h"
