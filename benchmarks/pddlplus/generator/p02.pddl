(define (problem generator-02)
  (:domain generator)
  (:objects gen - generator t1 t2 - tank)
  (:init
    (= (fuel gen) 38) (= (capacity gen) 39)
    (= (gen-duration) 143) (= (refuel-rate) 2)
    (= (tank-fuel t1) 46) (available t1)
    (= (tank-fuel t2) 60) (available t2))
  (:goal (and (generator-ran))))
