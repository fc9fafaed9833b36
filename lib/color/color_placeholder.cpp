// placeholder until the colour sources land
