// Placeholder for a library area that has no sources yet.
