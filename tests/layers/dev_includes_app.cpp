// Must NOT compile: the dev layer is called by the frame loop; it cannot call back into it.
#include "instruments.h"
#include "lab_app.h"
