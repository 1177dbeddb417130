namespace vitrum {}
