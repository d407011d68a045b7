// Placeholder: replaced by the module author.
#include "gallery.hpp"
