// The SVD's early stop (kernels/math/svd3.h, SNH_SVD_EARLY_EXIT): stopping
// before a sweep that would change nothing gives the values of the fixed
// SNH_SVD_SWEEPS sweeps. Both builds of the kernels' source, as the host
// and the devices' lanes programs run it, on the hard, random and
// extreme-spectrum matrices of test_svd.cpp and non-finite ones. On the
// device PointLanes compares the lanes programs with pocl's scalar kernels,
// which do not stop early.
#define SNH_DOUBLE 1
#define SNH_SWEEPS_TEST EarlyStopGivesTheFixedSweepsValuesDouble
#include "support/svd_sweeps_test.inc"
