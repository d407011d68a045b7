#pragma once
// Placeholder: the mesh preview renderer (owned by the mesh module's author).
