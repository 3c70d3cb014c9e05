; a character literal of two bytes: RRF reads one and wants the closing quote; the message quotes from the character's start
if x == 'é'
  M400
