; tpost0.g: tool 2 exists only when an edit to config.g creates it
G10 P2 X0 Y0 Z0
