(define (problem generator-05)
  (:domain generator)
  (:objects gen - generator t1 t2 - tank)
  (:init
    (= (fuel gen) 13) (= (capacity gen) 14)
    (= (gen-duration) 74) (= (refuel-rate) 2)
    (= (tank-fuel t1) 20) (available t1)
    (= (tank-fuel t2) 42) (available t2))
  (:goal (and (generator-ran))))
