// Must NOT compile: a lab (linking lab_app, as every lab does) cannot reach the dev layer's
// internals; lab 4 reads its two developer options from app.options().dev.
#include "lab_app.h"
#include "instruments.h"
