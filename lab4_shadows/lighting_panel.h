// lighting_panel.h — the "Lighting" window (UI only, since lab 2): pick the lighting and shading
// models, add / remove / edit lights and materials, show the light markers. Edits last until
// the scene file is reloaded (R, or the file changes on disk): a reload takes everything
// from the file again.
#pragma once

#include "lights.h"

void lighting_panel(Lighting& lighting);
