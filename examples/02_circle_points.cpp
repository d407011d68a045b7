// Placeholder: replaced by the module's author.
#include "gallery.hpp"
