#pragma once
// Depends on nothing.
