// Host reference in double precision.
#define SNH_DOUBLE 1
#include "reference/element_reference_impl.inc"
