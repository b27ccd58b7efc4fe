// A ctypes entry point for the official CEC 2017 / CEC 2022 C code, which leaves its
// globals to the caller's main(). Compiled together with one of the official files:
//   g++ -O0 -shared -fPIC -DYEAR=17 cec_driver.cpp cec17_test_func.cpp -o libcec17.so
// The official code opens input_data/... relative to the working directory, so the
// caller changes into a folder holding input_data/ before calling.
#include <stdlib.h>

double *OShift = NULL, *M = NULL, *y = NULL, *z = NULL, *x_bound = NULL;
int ini_flag = 0, n_flag, func_flag, *SS = NULL;

#if YEAR == 17
void cec17_test_func(double *, double *, int, int, int);
#define TEST_FUNC cec17_test_func
#else
void cec22_test_func(double *, double *, int, int, int);
#define TEST_FUNC cec22_test_func
#endif

extern "C" __attribute__((visibility("default"))) void evaluate(
    double *x, double *f, int nx, int mx, int func_num)
{
    TEST_FUNC(x, f, nx, mx, func_num);
}
