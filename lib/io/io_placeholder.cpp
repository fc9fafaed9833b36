// placeholder until the io sources land
