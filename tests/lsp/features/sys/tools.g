; Run by config.g.
global toolsReady = true
