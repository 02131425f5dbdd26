// Host reference in single precision.
#define SNH_DOUBLE 0
#include "material/element_reference_impl.inc"
