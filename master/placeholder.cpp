// Replaced by the master implementation.
