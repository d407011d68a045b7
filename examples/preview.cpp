#include "preview.hpp"
