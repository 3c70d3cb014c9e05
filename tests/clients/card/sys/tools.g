; tools.g: offsets for tool 1, which config.g never creates
G10 P1 X0 Y0 Z0
