#include "drape_test_util.h"
using namespace drape_test;
